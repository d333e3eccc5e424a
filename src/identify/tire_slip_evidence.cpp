#include "identify/tire_slip_evidence.hpp"

#include <algorithm>
#include <cmath>

#include "identify/measured_reset_state.hpp"

namespace upkie_rl {

namespace {

/// The IMU's velocity in world axes if both tires rolled without slipping.
Eigen::Vector3d rolling_imu_velocity(const RobotModel& model, const Observation& observation) {
  const Eigen::Matrix3d& base_to_world = observation.base_orientation.rotation_base_to_world;
  const Eigen::Vector3d angular_velocity =
      base_to_world * observation.base_orientation.angular_velocity;
  return measured_reset_state(model, observation).linear_velocity_base_to_world_in_world +
         angular_velocity.cross(base_to_world * model.imu_position_in_base());
}

/// The IMU's mean acceleration over the cycle that ends at `observation` [m/s^2], world axes.
Eigen::Vector3d imu_acceleration(const RobotModel& model, const Observation& observation,
                                 double gravity) {
  const Eigen::Matrix3d imu_to_world =
      observation.base_orientation.rotation_base_to_world * model.rotation_base_to_imu();
  return imu_to_world * observation.imu.raw_linear_acceleration -
         gravity * Eigen::Vector3d::UnitZ();
}

}  // namespace

bool logs_accelerometer(const RobotLog& log) {
  return std::any_of(log.cycles.begin(), log.cycles.end(), [](const LoggedCycle& cycle) {
    return !cycle.observation.imu.raw_linear_acceleration.isZero();
  });
}

std::vector<double> tire_slip_evidence(const RobotModel& model, const RobotLog& log,
                                       std::span<const std::size_t> cycles, double span,
                                       double gravity) {
  const auto span_cycles =
      std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(span / log.period())));
  std::vector<double> evidence(cycles.size(), 0.0);
  for (std::size_t n = 0; n < cycles.size(); ++n) {
    const std::size_t end = cycles[n];
    if (end < span_cycles || end >= log.cycles.size()) continue;
    const std::size_t begin = end - span_cycles;
    Eigen::Vector3d integrated = Eigen::Vector3d::Zero();
    for (std::size_t k = begin + 1; k <= end; ++k) {
      const double duration = log.cycles[k].time - log.cycles[k - 1].time;
      integrated += duration * imu_acceleration(model, log.cycles[k].observation, gravity);
    }
    const Eigen::Vector3d rolled = rolling_imu_velocity(model, log.cycles[end].observation) -
                                   rolling_imu_velocity(model, log.cycles[begin].observation);
    evidence[n] = (rolled - integrated).head<2>().norm();
  }
  return evidence;
}

}  // namespace upkie_rl
