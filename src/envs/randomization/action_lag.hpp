#pragma once
/// @file
/// ActionLag: pure delay and first-order lag between the servo commands an environment sends
/// and the ones its servos apply (the actuation of a real robot; ppo_balancer's sim-to-real
/// wrapper).

#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "base/option_table.hpp"
#include "sim/servo_command.hpp"
#include "sim/servo_delay_line.hpp"
#include "sim/servo_target_lag.hpp"

namespace upkie_rl {

/// Settings of ActionLag; zero everywhere is no lag and no delay.
struct ActionLagSettings {
  double time_constant_min = 0.0;  ///< τ drawn in U(min, max) at each reset [s].
  double time_constant_max = 0.0;  ///< 0: no first-order lag.
  int delay_steps = 0;             ///< Steps between an action and its application.
  /// Largest delay drawn at each reset, in U{delay_steps, ..., delay_steps_max}; 0 (or
  /// delay_steps) for a fixed delay. Why: a robot's agent runs late on some runs and not on
  /// others, and a policy trained on one fixed delay oscillates on another (docs/reality.md).
  int delay_steps_max = 0;
  /// The delay in seconds instead of steps [s], 0 for none: ActionLag rounds it to whole
  /// agent steps (a spine delays by whole cycles). Why: a suite's world of "20 ms of delay"
  /// must be 20 ms for a 100 Hz policy too, which `delay_steps` 1 made 10 ms.
  double delay_time = 0.0;

  bool any() const { return time_constant_max > 0.0 || largest_delay() > 0 || delay_time > 0.0; }
  /// The largest delay an episode can draw [steps], delay_time aside.
  int largest_delay() const {
    return delay_steps_max > delay_steps ? delay_steps_max : delay_steps;
  }

  /// What is wrong unless 0 <= min <= max (finite), the delays are in [0, 10000] steps,
  /// delay_time in [0, 1] s and not given with a delay in steps; "" if nothing.
  std::string problem() const;
  /// @throws std::invalid_argument with problem(), if any.
  void validate() const;

  /// Declares the options action_lag_min, action_lag_max, action_delay, action_delay_max
  /// and action_delay_time, and problem() as their rule.
  void declare_options(OptionTable& table);
};

/// The actuation between the servo commands of an environment and the ones its servos
/// apply: the command applied at step t is the one sent at step t − delay (the episode's
/// first command before it: the robot was already holding it when the episode began),
/// through a first-order lag of time constant τ on its targets (position, velocity,
/// feedforward torque; ServoTargetLag::step_mean, the filter's mean over the agent step).
/// τ and the delay are drawn at each reset (the delay when delay_steps_max is above
/// delay_steps); the randomisation scale multiplies τ's range and the delay (rounded).
///
/// Why on the servo commands, inside ServosEnv, and not on the agent's action: a task's
/// action becomes servo commands through the task's own law, and in residual mode through
/// the base controller; on the robot the whole command is late, the base's share included.
/// Lagging the agent's action left the velocity task's base controller unlagged, so a
/// residual policy met no latency where the classical baseline did (docs/reality.md).
/// Nothing is allocated after construction.
class ActionLag {
 public:
  /// @param step_duration The agent step the commands are held for [s]; a delay_time
  ///                      becomes the nearest whole number of them.
  /// @throws std::invalid_argument on settings out of their domain or a step not > 0.
  ActionLag(const ActionLagSettings& settings, double step_duration);

  /// Starts an episode: draws τ and the delay (a seed re-seeds their generator), scaled by
  /// `randomization_scale`.
  void reset(std::optional<std::uint64_t> seed, double randomization_scale);

  /// The command to apply this step, given the one sent this step (checked finite by the
  /// caller). The reference stays valid until the next call.
  const ServoAction& apply(const ServoAction& sent);

  /// The time constant of the current episode [s] (0 without lag).
  double time_constant() const { return time_constant_; }
  /// The delay of the current episode [steps].
  int delay() const { return delay_; }

 private:
  ActionLagSettings settings_;
  double step_duration_;
  std::mt19937_64 generator_{0};
  double time_constant_ = 0.0;
  int delay_ = 0;
  ServoTargetLag lag_;
  bool started_ = false;       ///< Whether the episode's first command has come.
  ServoDelayLine delay_line_;  ///< The last delay_ commands sent.
  ServoAction filtered_{};     ///< State of the first-order filter.
  ServoAction applied_{};      ///< The command applied this step.
};

}  // namespace upkie_rl
