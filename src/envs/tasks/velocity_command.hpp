#pragma once
/// @file
/// VelocityCommand: what the velocity-tracking task asks the robot to do, and the base
/// velocity it is compared with.

#include <array>

namespace upkie_rl {

/// Names of the command's velocity components, as columns of observations, record files and
/// viewer frames: forward velocity, then yaw rate.
inline constexpr std::array<const char*, 2> kCommandColumns = {"command.forward_velocity",
                                                               "command.yaw_rate"};
/// Name of the command's base height, as a column (after kCommandColumns) of observations,
/// record files and viewer frames, when the task has a height command.
inline constexpr const char* kHeightCommandColumn = "command.height";
/// Names of the followed command's rates over the coming step, as columns of observations
/// (after the height, with option observe_command_acceleration): forward acceleration
/// [m/s²], then yaw acceleration [rad/s²].
inline constexpr std::array<const char*, 2> kCommandAccelerationColumns = {
    "command.forward_acceleration", "command.yaw_acceleration"};
/// Names of the IMU's gravity-free linear acceleration in the base frame [m/s²], as
/// columns of observations (last, with option observe_acceleration): x forward, y left, z up.
inline constexpr std::array<const char*, 3> kImuAccelerationColumns = {
    "imu_acceleration.x", "imu_acceleration.y", "imu_acceleration.z"};
/// Name of the measured base height (record files, viewer frames).
inline constexpr const char* kMeasuredHeightColumn = "measured.height";

/// Height of Upkie's base origin above the floor, upright with straight legs [m]: the hips
/// 0.164 m below the base, thighs of 0.168 m, shins of 0.175 m and tires of radius 0.05 m
/// (LegKinematics::standing_height reads the same from the robot description).
inline constexpr double kStandingBaseHeight = 0.557;

/// Names of the measured base velocity's components (record files, viewer frames).
inline constexpr std::array<const char*, 2> kMeasuredVelocityColumns = {"measured.forward_velocity",
                                                                        "measured.yaw_rate"};

/// A command of the velocity task: drive forward at `forward_velocity` while turning at
/// `yaw_rate`, the base `height` above the floor. Set by the random resampler during training, by a
/// script (`rollout
/// --commands`), a runner or a browser (VelocityEnv::set_command_override).
struct VelocityCommand {
  double forward_velocity = 0.0;  ///< Along the base's heading [m/s], forward positive.
  double yaw_rate = 0.0;          ///< About the world's vertical [rad/s], counterclockwise.
  /// Base height above the floor [m] (LegKinematics::base_height); followed only by a task
  /// with a height command (option height_command), standing otherwise.
  double height = kStandingBaseHeight;

  bool operator==(const VelocityCommand&) const = default;
};

/// The base velocity the command is tracked against, in the same components.
struct BaseVelocity {
  double forward_velocity = 0.0;        ///< [m/s]
  double yaw_rate = 0.0;                ///< [rad/s]
  double height = kStandingBaseHeight;  ///< Base height above the floor [m].
};

}  // namespace upkie_rl
