#pragma once
/// @file
/// The state a simulation is put in at reset.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <stdexcept>

#include "model/joint_order.hpp"

namespace upkie_rl {

/// Initial state of the robot. Defaults: base at 0.6 m, upright, at rest, straight legs.
struct ResetState {
  /// Position of the base link origin in the world frame [m].
  Eigen::Vector3d position_base_in_world{0.0, 0.0, 0.6};
  /// Orientation of the base link in the world frame.
  Eigen::Quaterniond orientation_base_in_world = Eigen::Quaterniond::Identity();
  /// Linear velocity of the base link origin, world frame [m/s].
  Eigen::Vector3d linear_velocity_base_to_world_in_world = Eigen::Vector3d::Zero();
  /// Angular velocity of the base, base frame [rad/s].
  Eigen::Vector3d angular_velocity_base_in_base = Eigen::Vector3d::Zero();
  /// Joint angles in the standard order [rad].
  std::array<double, kNumServos> joint_configuration{};
  /// Joint velocities in the standard order [rad/s] (a replay from a measured state: the
  /// wheels of a rolling robot turn).
  std::array<double, kNumServos> joint_velocities{};
};

/// @throws std::invalid_argument when `state` has a non-finite value or a zero quaternion.
inline void validate_reset_state(const ResetState& state) {
  bool finite = state.position_base_in_world.allFinite() &&
                state.orientation_base_in_world.coeffs().allFinite() &&
                state.linear_velocity_base_to_world_in_world.allFinite() &&
                state.angular_velocity_base_in_base.allFinite();
  for (double angle : state.joint_configuration) finite = finite && std::isfinite(angle);
  for (double rate : state.joint_velocities) finite = finite && std::isfinite(rate);
  if (!finite) {
    throw std::invalid_argument(
        "reset state must be finite (position, orientation, velocities and joint angles)");
  }
  if (state.orientation_base_in_world.norm() < 1e-9) {
    throw std::invalid_argument("reset state: orientation quaternion must not be zero");
  }
}

}  // namespace upkie_rl
