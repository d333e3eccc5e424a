#include "envs/tasks/leg_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace upkie_rl {

namespace {

/// A crouch within this of straight legs is straight legs [m].
constexpr double kStraightTolerance = 1e-6;

/// Position in the base frame, at q = 0, of the axis of servo `servo` (its child link).
Eigen::Vector3d joint_position(const RobotModel& model, const std::vector<Eigen::Isometry3d>& poses,
                               std::size_t servo) {
  const Joint& joint = model.joints()[model.servo_joint(servo)];
  return poses[joint.child_link].translation();
}

}  // namespace

double largest_shin_tilt(double base_pitch, const std::array<double, 4>& leg_angles) {
  // The right leg's joints mirror the left's: its angles in the left convention are negated.
  const double left_shin = leg_angles[0] + leg_angles[1];
  const double right_shin = -(leg_angles[2] + leg_angles[3]);
  return std::max(std::abs(base_pitch - left_shin), std::abs(base_pitch - right_shin));
}

LegKinematics::LegKinematics(const RobotModel& model) : wheel_radius_(model.wheel_radius()) {
  const std::vector<Eigen::Isometry3d> poses = model.link_poses_at_zero();
  const Eigen::Vector3d hip = joint_position(model, poses, kLeftHip);
  const Eigen::Vector3d knee = joint_position(model, poses, kLeftKnee);
  const Eigen::Vector3d wheel = poses[model.tire_link(kLeftWheel)].translation();
  // The legs hang straight down at q = 0: lengths along the base's vertical.
  hip_depth_ = -hip.z();
  thigh_length_ = hip.z() - knee.z();
  shin_length_ = knee.z() - wheel.z();
  if (!(hip_depth_ > 0.0 && thigh_length_ > 0.0 && shin_length_ > 0.0 && wheel_radius_ > 0.0)) {
    throw std::invalid_argument("LegKinematics: the legs of " + model.path().string() +
                                " do not hang below the base at q = 0");
  }
}

Eigen::Vector2d LegKinematics::wheel_from_hip(double hip, double knee) const {
  const double shin_angle = hip + knee;  // from the downward vertical, forward positive
  return {thigh_length_ * std::sin(hip) + shin_length_ * std::sin(shin_angle),
          -thigh_length_ * std::cos(hip) - shin_length_ * std::cos(shin_angle)};
}

CrouchPose LegKinematics::crouch_pose(double base_height) const {
  // Two-link inverse kinematics for a wheel axle `reach` straight below the hip axis.
  const double longest = thigh_length_ + shin_length_;
  const double shortest = std::abs(thigh_length_ - shin_length_) + 1e-6;
  const double reach = std::clamp(base_height - hip_depth_ - wheel_radius_, shortest, longest);
  // Straight legs, exactly, within a micrometre: the observation carries the command as a
  // float, and 0.557f is 2e-8 m below 0.557.
  if (reach >= longest - kStraightTolerance) return {};
  const double cos_knee =
      (reach * reach - thigh_length_ * thigh_length_ - shin_length_ * shin_length_) /
      (2.0 * thigh_length_ * shin_length_);
  CrouchPose pose;
  pose.knee = -std::acos(std::clamp(cos_knee, -1.0, 1.0));  // the knee bends backward
  pose.hip = -std::atan2(shin_length_ * std::sin(pose.knee),
                         thigh_length_ + shin_length_ * std::cos(pose.knee));
  return pose;
}

double LegKinematics::height_at_shin_tilt(double shin_tilt) const {
  // Wheel under the hip: thigh_length·sin(hip) = shin_length·sin(tilt).
  const double sine =
      std::clamp(shin_length_ * std::sin(std::abs(shin_tilt)) / thigh_length_, 0.0, 1.0);
  return hip_depth_ + thigh_length_ * std::cos(std::asin(sine)) +
         shin_length_ * std::cos(shin_tilt) + wheel_radius_;
}

double LegKinematics::base_height(const std::array<double, 4>& leg_angles,
                                  const Eigen::Matrix3d& rotation_base_to_world) const {
  // The right leg's joints mirror the left's: its angles in the left convention are negated.
  const Eigen::Vector2d left = wheel_from_hip(leg_angles[0], leg_angles[1]);
  const Eigen::Vector2d right = wheel_from_hip(-leg_angles[2], -leg_angles[3]);
  const Eigen::Vector2d middle = 0.5 * (left + right);
  const Eigen::Vector3d axle_in_base(middle.x(), 0.0, middle.y() - hip_depth_);
  return wheel_radius_ - rotation_base_to_world.row(2).dot(axle_in_base);
}

}  // namespace upkie_rl
