#include "cli/velocity_view.hpp"

namespace upkie_rl::apps {

void add_velocity_charts(ViewSession& session) {
  session.extra_fields.insert(session.extra_fields.end(), kCommandColumns.begin(),
                              kCommandColumns.end());
  session.extra_fields.insert(session.extra_fields.end(), kMeasuredVelocityColumns.begin(),
                              kMeasuredVelocityColumns.end());
  session.charts.push_back(
      {"Forward velocity [m/s]",
       {{"command", kCommandColumns[0]}, {"measured", kMeasuredVelocityColumns[0]}}});
  session.charts.push_back(
      {"Yaw rate [rad/s]",
       {{"command", kCommandColumns[1]}, {"measured", kMeasuredVelocityColumns[1]}}});
}

void write_velocity_fields(const VelocityCommand& command, const BaseVelocity& measured,
                           std::span<double> extra) {
  extra[0] = command.forward_velocity;
  extra[1] = command.yaw_rate;
  extra[2] = measured.forward_velocity;
  extra[3] = measured.yaw_rate;
}

}  // namespace upkie_rl::apps
