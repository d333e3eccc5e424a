#pragma once
/// @file
/// The base observers: ground truth (`sim.base`) and attitude (`base_orientation`).

#include "sim/measured_state.hpp"
#include "sim/observation.hpp"

namespace upkie_rl {

/// Pitch [rad] of a base orientation as the reference PyBullet backend computes it: the
/// ZYX Euler pitch, positive when leaning forward, independent of yaw.
double base_pitch(const Eigen::Quaterniond& orientation_base_in_world);

/// Yaw [rad] of a base orientation: the heading of the base's x axis in the world's
/// horizontal plane, counterclockwise from the world's x axis, in [-pi, pi].
double base_yaw(const Eigen::Matrix3d& rotation_base_to_world);

/// Fills `sim_base` (ground truth) and `base_orientation` from the measured base.
void observe_base(const MeasuredBase& base, SimBaseObservation& sim_base,
                  BaseOrientationObservation& base_orientation);

/// Fills `base_orientation` (the attitude the robot's IMU gives) from the measured base,
/// whose world frame must have its z axis against gravity.
void observe_attitude(const MeasuredBase& base, BaseOrientationObservation& base_orientation);

}  // namespace upkie_rl
