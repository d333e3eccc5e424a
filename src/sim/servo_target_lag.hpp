#pragma once
/// @file
/// ServoTargetLag: one step of a first-order lag y' = (u − y)/τ on the targets of a servo
/// command (position, velocity, feedforward torque), the law the environments' actuation
/// (ActionLag) and the simulation spine's (ServoActionLag) share.
///
/// Why two ways to apply it: the spine filters at each 1 ms simulation step and applies the
/// filter's value, which is what a servo filtering continuously applies to within that
/// millisecond. An environment holds one command for a whole agent step (20 ms at 50 Hz);
/// applying the filter's end-of-step value there would make any τ under a step almost no
/// lag (the former α = min(1, dt/τ) was none at all for τ ≤ dt), so it applies the filter's
/// mean over the step instead: with a servo law linear in its targets, the same mean
/// torque as filtering at every physics step, to first order in the joints' motion.

#include "sim/servo_command.hpp"

namespace upkie_rl {

/// The lag of one time constant over one step, as the shares of the gap u − y closed.
struct ServoTargetLag {
  double state_gain = 1.0;    ///< Share of the gap the filter's state closes over the step.
  double applied_gain = 1.0;  ///< Share of it the command applied over the step closes.

  /// The filter's value at the step's end is applied (a filter stepped at the physics rate):
  /// both gains 1 − exp(−duration/τ). τ = 0 is no lag.
  /// @throws std::invalid_argument unless τ ≥ 0 and duration > 0, both finite.
  static ServoTargetLag step_end(double time_constant, double duration);
  /// The filter's mean over the step is applied: applied_gain 1 − (τ/duration)(1 −
  /// exp(−duration/τ)). τ = 0 is no lag.
  /// @throws std::invalid_argument unless τ ≥ 0 and duration > 0, both finite.
  static ServoTargetLag step_mean(double time_constant, double duration);

  /// Whether this lags at all (τ > 0).
  bool any() const { return state_gain < 1.0; }

  /// One step of one target held at `commanded`: `state` closes state_gain of the gap,
  /// `applied` becomes the value to apply; a NaN on either side restarts at `commanded`.
  void step_target(double commanded, double& state, double& applied) const;

  /// One step with `command` held: `state`'s targets move towards the command's, and
  /// `applied` becomes the command with the targets to apply. Gains and torque limits pass
  /// as commanded. A NaN target on either side ("no position loop") restarts the filter at
  /// the command's value. `applied` must not be `state`.
  void step(const ServoAction& command, ServoAction& state, ServoAction& applied) const;
};

}  // namespace upkie_rl
