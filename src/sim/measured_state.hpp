#pragma once
/// @file
/// What a physics engine measures of the robot, before any observer turns it into an
/// Observation. Every backend fills these; the observers are shared.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

#include "model/joint_order.hpp"

namespace upkie_rl {

/// Joint angles, velocities and applied torques in the standard order.
struct MeasuredJoints {
  std::array<double, kNumServos> position{};  ///< [rad]
  std::array<double, kNumServos> velocity{};  ///< [rad/s]
  std::array<double, kNumServos> torque{};    ///< Torque of the servo law [N.m].
};

/// Pose and velocity of the base link (not its centre of mass) in the world frame.
struct MeasuredBase {
  Eigen::Isometry3d pose_in_world = Eigen::Isometry3d::Identity();
  Eigen::Vector3d linear_velocity_in_world = Eigen::Vector3d::Zero();   ///< Of the origin [m/s].
  Eigen::Vector3d angular_velocity_in_world = Eigen::Vector3d::Zero();  ///< [rad/s]
};

}  // namespace upkie_rl
