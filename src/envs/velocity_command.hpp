#pragma once
/// @file
/// VelocityCommand: what the velocity-tracking task asks the robot to do, and the base
/// velocity it is compared with.

#include <array>

namespace upkie_rl {

/// Names of the command's components, as columns of observations, record files and viewer
/// frames: forward velocity, then yaw rate.
inline constexpr std::array<const char*, 2> kCommandColumns = {"command.forward_velocity",
                                                               "command.yaw_rate"};

/// Names of the measured base velocity's components (record files, viewer frames).
inline constexpr std::array<const char*, 2> kMeasuredVelocityColumns = {"measured.forward_velocity",
                                                                        "measured.yaw_rate"};

/// A command of the velocity task: drive forward at `forward_velocity` while turning at
/// `yaw_rate`. Set by the random resampler during training, by a script (`rollout
/// --commands`), a runner or a browser (VelocityEnv::set_command_override).
struct VelocityCommand {
  double forward_velocity = 0.0;  ///< Along the base's heading [m/s], forward positive.
  double yaw_rate = 0.0;          ///< About the world's vertical [rad/s], counterclockwise.

  bool operator==(const VelocityCommand&) const = default;
};

/// The base velocity the command is tracked against, in the same components.
struct BaseVelocity {
  double forward_velocity = 0.0;  ///< [m/s]
  double yaw_rate = 0.0;          ///< [rad/s]
};

}  // namespace upkie_rl
