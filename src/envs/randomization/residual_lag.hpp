#pragma once
/// @file
/// ResidualLag: a first-order lag on a residual policy's own action, its time constant drawn
/// per episode: a training regulariser, not the robot's actuation (that is ActionLag, on
/// the whole servo command).
///
/// Why: until 2026-11-29 the actuation lag of configs/velocity.yaml (U(0, 80 ms)) lagged
/// the agent's residual only, the base controller's share escaping it. That was wrong as
/// a model of the robot, but the policies trained that way tracked 28-32 % better than the
/// baseline on the reality suite; the same lag on the whole command, or 0-20 ms of it,
/// gave 1-19 % (docs/reality.md). The residual's lag makes the policy's corrections work
/// when they come smoothed, which keeps them smooth. It stays in training: evaluations
/// and the robot run without it (a randomisation option).

#include <cstdint>
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "sim/servo_target_lag.hpp"

namespace upkie_rl {

/// The agent's action a passes y' = (a − y)/τ, the filter's mean over each step applied
/// (the law of ServoTargetLag::step_mean), from y = 0 at reset; τ drawn in U(0, max) at each
/// reset, times the randomisation scale. Nothing is allocated after construction.
class ResidualLag {
 public:
  /// @param max_time_constant Largest τ [s], > 0.
  /// @param step_duration The agent step [s], > 0.
  /// @param size Components of the action.
  /// @throws std::invalid_argument on a bound that is not finite and positive.
  ResidualLag(double max_time_constant, double step_duration, std::size_t size);

  /// Starts an episode: draws τ (a seed re-seeds its generator) and zeroes the filter.
  void reset(std::optional<std::uint64_t> seed, double randomization_scale);
  /// Filters `action` in place.
  void apply(std::span<float> action);

  /// The time constant of the current episode [s].
  double time_constant() const { return time_constant_; }

 private:
  double max_time_constant_;
  double step_duration_;
  std::mt19937_64 generator_{0};
  double time_constant_ = 0.0;
  ServoTargetLag lag_;
  std::vector<double> state_;
};

}  // namespace upkie_rl
