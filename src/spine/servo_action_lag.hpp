#pragma once
/// @file
/// ServoActionLag: the actuation of a real robot played by the simulation spine: a pure
/// delay and a first-order lag between the commands an agent sends and the ones the
/// simulated servos apply.
///
/// Why: a robot's commands reach its moteus servos a few milliseconds late (the agent's
/// cycle, the spine's, the CAN bus) and its motors follow them with a lag; the environments
/// model this on the agent's side (ActionLag), but a simulation spine that plays "reality"
/// for an agent it does not know (`upkie-rl spine --action-delay/--action-lag`, the
/// sim2real demo) must do it on its own side, where the agent cannot see it.

#include <string>
#include <vector>

#include "sim/servo_command.hpp"
#include "sim/servo_delay_line.hpp"
#include "sim/servo_target_lag.hpp"

namespace upkie_rl {

/// Settings of ServoActionLag; zero delay and zero time constant apply commands as sent.
struct ServoActionLagSettings {
  int delay_steps = 0;          ///< Simulation steps between a command and its application.
  double time_constant = 0.0;   ///< First-order lag τ [s]; 0: none.
  double step_duration = 1e-3;  ///< Duration of one simulation step [s].

  /// Whether commands are delayed or filtered.
  bool any() const { return delay_steps > 0 || time_constant > 0.0; }
  /// What is wrong unless the delay is in [0, 100000] steps, τ in [0, 10] s and the step
  /// positive (all finite); "" if nothing.
  std::string problem() const;
};

/// The command applied at step t is the one sent at step t - delay_steps (the reset's
/// command before), whose position, velocity and feedforward torque pass a first-order
/// filter y <- y + (1 - exp(-dt/τ)) (u - y): the exact discretisation, so the same τ gives
/// the same response in real time (1 ms steps) and on request (one agent step per step).
/// A NaN position ("no position loop") passes unfiltered, and the filter restarts from the
/// first finite position after it. Gains and torque limits pass unfiltered, delayed.
/// Nothing is allocated after construction.
class ServoActionLag {
 public:
  /// @throws SpineError with ServoActionLagSettings::problem(), if any.
  explicit ServoActionLag(const ServoActionLagSettings& settings);

  /// Starts an episode: every delayed command and the filter's state become `initial`.
  void reset(const ServoAction& initial);

  /// The command to apply this step, given the one sent this step. The reference stays
  /// valid until the next call.
  const ServoAction& apply(const ServoAction& sent);

  const ServoActionLagSettings& settings() const { return settings_; }

 private:
  ServoActionLagSettings settings_;
  ServoTargetLag lag_;         ///< ServoTargetLag::step_end(τ, dt).
  ServoDelayLine delay_line_;  ///< The last delay_steps commands sent.
  ServoAction filtered_{};     ///< The filter's state.
  ServoAction applied_{};      ///< The command applied this step: the state's targets.
};

}  // namespace upkie_rl
