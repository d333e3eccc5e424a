#pragma once
/// @file
/// A spine log of a simulated robot balancing under random ground-velocity steps: the logs
/// the identification tests fit, with physics they know.

#include <cstdint>
#include <filesystem>
#include <string>

#include "envs/core/env_options.hpp"

namespace upkie_rl {

/// How the simulated robot is driven.
struct ExcitationSettings {
  double duration = 4.0;   ///< [s]
  double amplitude = 0.6;  ///< Largest ground-velocity step [m/s].
  double hold_min = 0.2;   ///< Each step held for U(hold_min, hold_max) [s].
  double hold_max = 0.5;   ///< [s]
  std::uint64_t seed = 0;  ///< Of the steps and of the environment.
};

/// Runs `env_id` (a servos environment, e.g. Upkie-Bullet-Servos, with the "real" physics in
/// `options`: masses, friction, action_delay, action_lag_min = _max) for settings.duration:
/// the wheels balance the pitch (ground velocity 10·pitch + ground position + 0.1·its rate, the
/// pendulum's PD law) plus random ground-velocity steps, the legs held. Writes each step to a
/// spine log at `path`: the observation, then the commands sent after it (before the
/// environment's delay and lag, as a robot's spine logs what the agent sent).
/// @throws std::invalid_argument on a bad id or option; RobotLogError on a write error.
void write_excitation_log(const std::string& env_id, const EnvOptions& options,
                          const ExcitationSettings& settings, const std::filesystem::path& path);

}  // namespace upkie_rl
