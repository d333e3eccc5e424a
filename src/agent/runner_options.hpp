#pragma once
/// @file
/// The options of the robot runner (`upkie-rl-agent`).

#include <filesystem>
#include <string>

#include "agent/supervisor_limits.hpp"

namespace upkie_rl {

/// What `upkie-rl-agent` runs and how.
struct RunnerOptions {
  std::filesystem::path model;      ///< A `.ckpt` of `upkie-rl train` (final model or checkpoint).
  std::string shm_name = "/upkie";  ///< Shared-memory name of the spine.
  double duration = 0.0;            ///< Stop after this long [s]; 0 runs until stopped.
  std::filesystem::path record;     ///< Flight record CSV; empty for none.
  bool dry_run = false;             ///< Send stop commands only; log the policy's commands.
  int open_tries = 10;              ///< Attempts at opening the spine, 1 s apart.
  /// Velocity tasks: a CSV file of rows time,vx,wz (`rollout --commands`'s format), or "-"
  /// for lines vx,wz on the standard input; empty for none.
  std::string commands;
  bool keyboard = false;  ///< Velocity tasks: steer with the keys of the terminal.
  SupervisorLimits limits;
};

}  // namespace upkie_rl
