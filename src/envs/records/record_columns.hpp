#pragma once
/// @file
/// The columns of a record file (envs/records/episode_recorder.hpp) declared once, for its writer
/// (EpisodeRecorder) and its reader (`upkie-rl render`, `upkie-rl view`): a column's name
/// and the field its value comes from or goes to are written side by side here, so that
/// neither side counts column offsets.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

#include "envs/tasks/velocity_command.hpp"
#include "model/joint_order.hpp"

namespace upkie_rl {

/// The columns every row starts with: episode, step, then the time of the observation.
inline constexpr const char* kEpisodeColumn = "episode";
inline constexpr const char* kStepColumn = "step";
inline constexpr const char* kTimeColumn = "t";
/// The outcome of the step, after the observation's and the action's columns.
inline constexpr const char* kRewardColumn = "reward";
inline constexpr const char* kTerminatedColumn = "terminated";
inline constexpr const char* kTruncatedColumn = "truncated";
/// Each action component's column is this prefix and the component's name.
inline constexpr const char* kActionColumnPrefix = "action.";

/// The simulator's ground truth in a row (NaN without one, e.g. a spine run).
struct RecordedPose {
  Eigen::Vector3d base_position = Eigen::Vector3d::Zero();  ///< World frame [m].
  Eigen::Quaterniond base_orientation = Eigen::Quaterniond::Identity();
  std::array<double, kNumServos> joint_angles{};  ///< Standard order [rad].
};

/// What the robot measures, in a row.
struct RecordedMeasurement {
  double pitch = 0.0;            ///< Base pitch [rad].
  double ground_position = 0.0;  ///< Wheel odometry [m].
};

/// Calls `visit(column, value)` for each ground-truth column, in file order: base_x,
/// base_y, base_z, base_qw, base_qx, base_qy, base_qz, then the six joint angles by joint
/// name. `Pose` is RecordedPose or any struct with the same members (the renderer's).
template <typename Pose, typename Visitor>
void visit_pose_columns(Pose& pose, Visitor&& visit) {
  visit("base_x", pose.base_position.x());
  visit("base_y", pose.base_position.y());
  visit("base_z", pose.base_position.z());
  visit("base_qw", pose.base_orientation.w());
  visit("base_qx", pose.base_orientation.x());
  visit("base_qy", pose.base_orientation.y());
  visit("base_qz", pose.base_orientation.z());
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    visit(kServoNames[servo], pose.joint_angles[servo]);
  }
}

/// Calls `visit(column, value)` for the measured columns, after the ground truth's.
template <typename Measurement, typename Visitor>
void visit_measurement_columns(Measurement& measurement, Visitor&& visit) {
  visit("pitch", measurement.pitch);
  visit("ground_position", measurement.ground_position);
}

/// Calls `visit(column, value)` for the measured base velocity of a velocity task
/// (kMeasuredVelocityColumns), after the measured columns.
template <typename Velocity, typename Visitor>
void visit_measured_velocity_columns(Velocity& measured, Visitor&& visit) {
  visit(kMeasuredVelocityColumns[0], measured.forward_velocity);
  visit(kMeasuredVelocityColumns[1], measured.yaw_rate);
}

/// Calls `visit(column, value)` for a velocity task's command (kCommandColumns), which the
/// observation's columns hold.
template <typename Command, typename Visitor>
void visit_command_columns(Command& command, Visitor&& visit) {
  visit(kCommandColumns[0], command.forward_velocity);
  visit(kCommandColumns[1], command.yaw_rate);
}

}  // namespace upkie_rl
