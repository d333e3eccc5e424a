#include "sim/base_observer.hpp"

#include <algorithm>
#include <cmath>

namespace upkie_rl {

double base_pitch(const Eigen::Quaterniond& q) {
  const double sin_pitch = std::clamp(2.0 * (q.w() * q.y() - q.z() * q.x()), -1.0, 1.0);
  return std::asin(sin_pitch);
}

double base_yaw(const Eigen::Matrix3d& rotation_base_to_world) {
  return std::atan2(rotation_base_to_world(1, 0), rotation_base_to_world(0, 0));
}

void observe_base(const MeasuredBase& base, SimBaseObservation& sim_base,
                  BaseOrientationObservation& base_orientation) {
  const Eigen::Matrix3d rotation_base_to_world = base.pose_in_world.linear();
  sim_base.position = base.pose_in_world.translation();
  sim_base.orientation = Eigen::Quaterniond(rotation_base_to_world);
  sim_base.linear_velocity = base.linear_velocity_in_world;
  sim_base.angular_velocity = rotation_base_to_world.transpose() * base.angular_velocity_in_world;
  base_orientation.pitch = base_pitch(sim_base.orientation);
  base_orientation.angular_velocity = sim_base.angular_velocity;
  base_orientation.rotation_base_to_world = rotation_base_to_world;
}

void observe_attitude(const MeasuredBase& base, BaseOrientationObservation& base_orientation) {
  const Eigen::Matrix3d rotation_base_to_world = base.pose_in_world.linear();
  base_orientation.pitch = base_pitch(Eigen::Quaterniond(rotation_base_to_world));
  base_orientation.angular_velocity =
      rotation_base_to_world.transpose() * base.angular_velocity_in_world;
  base_orientation.rotation_base_to_world = rotation_base_to_world;
}

}  // namespace upkie_rl
