#pragma once
/// @file
/// ActionLag: pure delay and first-order lag between the agent's action and the one the
/// environment applies (the actuation of a real robot; ppo_balancer's sim-to-real wrapper).

#include <random>
#include <string>
#include <vector>

#include "base/option_table.hpp"
#include "envs/wrappers/env_wrapper.hpp"

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

  bool any() const { return time_constant_max > 0.0 || largest_delay() > 0; }
  /// The largest delay an episode can draw [steps].
  int largest_delay() const {
    return delay_steps_max > delay_steps ? delay_steps_max : delay_steps;
  }

  /// What is wrong unless 0 <= min <= max (finite) and the delays are in [0, 10000]; "" if
  /// nothing.
  std::string problem() const;
  /// @throws std::invalid_argument with problem(), if any.
  void validate() const;

  /// Declares the options action_lag_min, action_lag_max, action_delay and
  /// action_delay_max, and problem() as their rule.
  void declare_options(OptionTable& table);
};

/// The action applied at step t is the agent's action of step t - delay (the neutral
/// action before the episode's first), filtered by y ← y + (dt/τ)(u − y) per component,
/// starting from the neutral action; a NaN component (a servo's "no position loop") passes
/// unfiltered. The delay is drawn per episode when delay_steps_max is above delay_steps.
/// Randomisation scaling multiplies τ's range and the delay (rounded).
class ActionLag final : public EnvWrapper {
 public:
  /// @throws std::invalid_argument on a null env or settings out of their domain.
  ActionLag(std::unique_ptr<Env> env, const ActionLagSettings& settings);

  /// The time constant of the current episode [s] (0 without lag).
  double time_constant() const { return time_constant_; }
  /// The delay of the current episode [steps].
  int delay() const { return delay_; }

  void reset(std::optional<std::uint64_t> seed, std::span<float> observation) override;
  StepResult step(std::span<const float> action, std::span<float> observation) override;
  void set_randomization_scale(double scale) override;

 private:
  ActionLagSettings settings_;
  double scale_ = 1.0;
  std::mt19937_64 generator_{0};
  double time_constant_ = 0.0;
  int delay_ = 0;
  std::vector<float> neutral_;
  std::vector<float> queue_;  ///< Ring of the last delay_ actions, oldest at head_.
  std::size_t head_ = 0;
  std::vector<float> delayed_;   ///< The action leaving the delay line.
  std::vector<float> filtered_;  ///< State of the first-order filter.
};

}  // namespace upkie_rl
