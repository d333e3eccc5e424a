#pragma once
/// @file
/// ResidualLag: a first-order filter on a residual policy's own action, part of the policy
/// (residual_filter, kept wherever it runs), its time constant optionally drawn per episode
/// in training (residual_lag_max): not the robot's actuation (that is ActionLag, on the
/// whole servo command).
///
/// Why: until 2026-11-29 the actuation lag of configs/velocity.yaml (U(0, 80 ms)) lagged
/// the agent's residual only, the base controller's share escaping it. That was wrong as
/// a model of the robot, but the policies trained that way tracked 28-32 % better than the
/// baseline on the reality suite; the same lag on the whole command, or 0-20 ms of it,
/// gave 1-19 % (docs/reality.md). The residual's lag makes the policy's corrections work
/// when they come smoothed; it does not make them smooth without it. Until the night of
/// 2026-11-29 the draw was all there was, a randomisation option, so evaluations and the
/// robot ran the policy unfiltered: its corrections chattered at the agent's Nyquist rate
/// (25 Hz; 23-80 % of the yaw error's power on three seeds, the wheel-differential action
/// changing 7-25 times as much per step as the baseline's). With a 20 ms filter kept
/// (residual_filter), the README evaluation's yaw error fell from 0.206-0.336 to
/// 0.165-0.193 rad/s and the suite's tracking from 8-32 % to 33-38 % better than the
/// baseline's on the same three policies (docs/reality.md). It lives beside the
/// randomisation because its draw is one.

#include <cstdint>
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "sim/servo_target_lag.hpp"

namespace upkie_rl {

/// The agent's action a passes y' = (a − y)/τ, the filter's mean over each step applied
/// (the law of ServoTargetLag::step_mean), from y = 0 at reset; τ is the nominal time
/// constant, or, when a training draw is set, drawn in U(0, max) at each reset, times the
/// randomisation scale. Nothing is allocated after construction.
class ResidualLag {
 public:
  /// @param time_constant The nominal τ [s] (residual_filter), >= 0.
  /// @param max_draw Largest τ drawn per episode in training [s] (residual_lag_max), >= 0;
  ///                 0: τ is the nominal one.
  /// @param step_duration The agent step [s], > 0.
  /// @param size Components of the action.
  /// @throws std::invalid_argument on a value that is not finite, a negative time constant,
  ///         a step that is not positive, or a nominal τ above a draw's largest.
  ResidualLag(double time_constant, double max_draw, double step_duration, std::size_t size);

  /// Starts an episode: draws τ if a draw is set (a seed re-seeds its generator), and zeroes
  /// the filter.
  void reset(std::optional<std::uint64_t> seed, double randomization_scale);
  /// Filters `action` in place.
  void apply(std::span<float> action);

  /// The time constant of the current episode [s].
  double time_constant() const { return time_constant_; }

 private:
  double max_draw_;
  double step_duration_;
  std::mt19937_64 generator_{0};
  double time_constant_ = 0.0;
  ServoTargetLag lag_;
  std::vector<double> state_;
};

}  // namespace upkie_rl
