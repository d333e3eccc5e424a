#pragma once
/// @file
/// LegKinematics: the planar hip-knee-wheel chain of Upkie's legs, for the body-height
/// command of the velocity task: the base height a leg pose gives, and the crouch pose
/// (wheel under the hip) that gives a base height.

#include <array>

#include <Eigen/Core>

#include "model/robot_model.hpp"

namespace upkie_rl {

/// Largest tilt of a shin from the vertical that keeps the ankle clear of the floor [rad].
/// The description's ankle collision box (92 × 68 mm in the wheel's plane, centred 2 mm
/// above the axle) reaches 57 mm from the axle at its corners, beyond the 50 mm tire: its
/// lowest corner touches a flat floor when the shin tilts about 0.43 rad, less once the
/// soft tire sinks by a few millimetres; at 0.38 rad it clears the floor by about 3 mm.
inline constexpr double kMaxShinTilt = 0.38;

/// The larger of the two shins' tilts from the world's vertical in the legs' sagittal plane
/// [rad, >= 0]: the angle the ankle brackets' clearance depends on (kMaxShinTilt).
/// `base_pitch` is the base's forward lean [rad] (velocity_task_pitch: positive when the top
/// leans forward) and `leg_angles` the (left hip, left knee, right hip, right knee) angles;
/// a shin's angle from the base's downward vertical is hip + knee in the left leg's
/// convention (forward positive), and leaning the base forward swings it back by the lean.
/// So straight legs tilt with the base, and a forward swing of the legs can keep the shins
/// upright while the base leans. Allocation-free.
double largest_shin_tilt(double base_pitch, const std::array<double, 4>& leg_angles);

/// Hip and knee angles of the left leg [rad]; the right leg mirrors them (negated).
struct CrouchPose {
  double hip = 0.0;
  double knee = 0.0;

  /// The pose's joint angles in the order left hip, left knee, right hip, right knee: the
  /// right leg mirrors the left (its joints turn the other way).
  std::array<double, 4> leg_angles() const { return {hip, knee, -hip, -knee}; }
};

/// Lengths of the legs in their sagittal plane, read from the robot description with all
/// joints at 0 (legs straight down): the base origin is `hip_depth` above the hip axes,
/// the knee axis `thigh_length` below the hip, the wheel axle `shin_length` below the knee.
/// Positive left-hip and left-knee angles swing what they carry forward (the right leg's
/// joints mirror them), so the symmetric crouch is hips (+h, -h), knees (k, -k) with k < 0.
class LegKinematics {
 public:
  /// @throws std::invalid_argument when the description's legs are not planar chains
  ///         hanging below the base (zero or negative lengths).
  explicit LegKinematics(const RobotModel& model);

  /// Base height above the floor with straight legs, upright [m] (0.557 for Upkie).
  double standing_height() const {
    return hip_depth_ + thigh_length_ + shin_length_ + wheel_radius_;
  }

  /// The crouch pose whose wheel axle lies straight below the hip axis (in the base frame)
  /// and whose upright base is `base_height` above the floor [m], clamped to what the leg
  /// reaches (straight legs at most). Allocation-free.
  CrouchPose crouch_pose(double base_height) const;

  /// Base height of the crouch pose (wheel under the hip, base upright) whose shins tilt by
  /// `shin_tilt` from the base's vertical [m]: the lowest crouch that keeps that tilt.
  double height_at_shin_tilt(double shin_tilt) const;

  /// Base height above the floor [m]: the wheel radius plus the height of the base origin
  /// above the midpoint of the two wheel axles, along the world's vertical, with
  /// `leg_angles` the (left hip, left knee, right hip, right knee) angles and
  /// `rotation_base_to_world` the base's attitude (what the IMU measures). The same on a
  /// robot and in simulation; it equals the ground truth on a flat floor, up to the tires'
  /// sinking. Allocation-free.
  double base_height(const std::array<double, 4>& leg_angles,
                     const Eigen::Matrix3d& rotation_base_to_world) const;

  double hip_depth() const { return hip_depth_; }
  double thigh_length() const { return thigh_length_; }
  double shin_length() const { return shin_length_; }
  double wheel_radius() const { return wheel_radius_; }

 private:
  /// Wheel axle relative to the hip axis in the leg's sagittal plane (x forward, z up) for
  /// hip and knee angles in the left leg's convention [m].
  Eigen::Vector2d wheel_from_hip(double hip, double knee) const;

  double hip_depth_ = 0.0;
  double thigh_length_ = 0.0;
  double shin_length_ = 0.0;
  double wheel_radius_ = 0.0;
};

}  // namespace upkie_rl
