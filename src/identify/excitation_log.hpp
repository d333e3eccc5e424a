#pragma once
/// @file
/// A spine log of a simulated robot balancing under random velocity steps: the logs the
/// identification tests and benchmarks fit, with physics they know.

#include <cstdint>
#include <filesystem>
#include <string>

#include "envs/controllers/velocity_balancer_gains.hpp"
#include "envs/core/env_options.hpp"

namespace upkie_rl {

/// The velocity task's balance law as `upkie-rl rollout --controller lqr` designs it on
/// Upkie-Bullet-Velocity (nominal robot, 50 Hz), rounded, without its acceleration
/// feedforward (with it, the benchmark's robot fell after 6 s on MuJoCo at 200 Hz). Fixed
/// rather than designed per log (7 s a design): it holds both engines' robots with the
/// identification tests' and benchmarks' hidden physics, and write_excitation_log refuses a
/// log where it does not.
inline VelocityBalancerGains excitation_balance_gains() {
  VelocityBalancerGains gains;
  gains.feedback = {11.8, 0.36, 2.6, 0.72};
  gains.pitch_offset = 0.0176;
  gains.pitch_per_velocity = 0.063;
  gains.command_per_velocity = 1.014;
  return gains;
}

/// How the simulated robot is driven.
struct ExcitationSettings {
  double duration = 4.0;       ///< [s]
  double amplitude = 1.0;      ///< Largest forward velocity command [m/s].
  double yaw_amplitude = 0.3;  ///< Largest yaw rate command [rad/s] (open loop).
  /// Largest step added to the balance law's ground velocity [m/s]: the wheels leap. 0 by
  /// default: on 60 s logs, kicks of 0.3 m/s make the fitted delay exact on every seed of
  /// either engine, but Bullet's friction is no closer (within 5 % on 4 seeds of 8, 3
  /// without) and a Bullet fit takes up to 8 % more evaluations (docs/identify.md).
  double kick_amplitude = 0.0;
  double hold_min = 0.2;   ///< Each command held for U(hold_min, hold_max) [s].
  double hold_max = 0.5;   ///< [s]
  std::uint64_t seed = 0;  ///< Of the commands and of the environment.
  VelocityBalancerGains balance = excitation_balance_gains();
};

/// Runs `env_id` (a servos environment, e.g. Upkie-Bullet-Servos, with the "real" physics in
/// `options`: masses, friction, action_delay, action_lag_min = _max) for settings.duration:
/// the wheels balance the robot with the velocity task's law (ForwardBalanceLaw, its filters
/// at the environment's rate) following random forward velocity commands, plus random steps
/// of the ground velocity (its excitation), and turn it by random yaw rates; the legs are
/// held. After half a second of balance (the simulators release the robot above the floor;
/// a robot's log starts with it on its wheels), writes each step to a spine log at `path`:
/// the observation, then the commands sent after it (before the environment's delay and
/// lag, as a robot's spine logs what the agent sent).
/// @throws std::invalid_argument on a bad id or option; RobotLogError on a write error;
///         Error when the robot falls (its base tilts beyond 1 rad): a log of a fallen robot
///         is not one to identify a standing robot from.
void write_excitation_log(const std::string& env_id, const EnvOptions& options,
                          const ExcitationSettings& settings, const std::filesystem::path& path);

}  // namespace upkie_rl
