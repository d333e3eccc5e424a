#pragma once
/// @file
/// FloorSlope: a sloped floor simulated as a flat floor under tilted gravity.

#include <Eigen/Core>

namespace upkie_rl {

/// A floor tilted by `pitch` about the robot's initial lateral axis and `roll` about its
/// initial forward axis, simulated as the flat floor z = 0 of the engine's world frame (the
/// "floor frame") under gravity tilted the other way. The level frame is the frame of the
/// real slope's world: z up against gravity, the same heading as the floor frame.
///
/// With H the rotation by the robot's initial heading about z, Ry and Rx rotations about y
/// and x: rotation_floor_to_level = H · Ry(-pitch) · Rx(roll) · Hᵀ, and gravity in the floor
/// frame is rotation_floor_to_levelᵀ · (0, 0, -g). Positive pitch: the floor rises ahead of
/// the robot, gravity pulls it backward; positive roll: the floor rises to its left,
/// gravity pulls it to its right.
struct FloorSlope {
  /// Rotation from the floor frame to the level frame (identity on a flat floor).
  Eigen::Matrix3d rotation_floor_to_level = Eigen::Matrix3d::Identity();
  /// Gravity in the floor frame [m/s^2].
  Eigen::Vector3d gravity_in_floor = Eigen::Vector3d::Zero();
  /// Whether the floor is tilted; a flat floor's values are exact (no rounding).
  bool tilted = false;
};

/// The slope of `pitch` and `roll` [rad] for a robot whose heading at reset is `heading`
/// [rad] (counterclockwise from the x axis), under gravity of magnitude `gravity` [m/s^2].
/// With pitch and roll both zero: the identity and exactly (0, 0, -gravity).
FloorSlope make_floor_slope(double pitch, double roll, double heading, double gravity);

}  // namespace upkie_rl
