#pragma once
/// @file
/// The seed's balance reward (eq. 9 for the pendulum, eq. 22 for the servos task).

#include "base/option_table.hpp"

namespace upkie_rl {

/// Weights of the balance reward.
struct BalanceRewardWeights {
  double w_theta = 2.0;      ///< Pitch [1/rad^2].
  double w_theta_dot = 0.5;  ///< Pitch rate [s^2/rad^2].
  double w_p_dot = 0.5;      ///< Ground velocity [s^2/m^2].
  double w_a = 1.0;          ///< Action.
  double w_s = 2.0;          ///< First difference of the action (smoothness).
  double w_accel = 1.5;      ///< Second difference of the action.

  /// Seed eq. 10-15 (the default).
  static BalanceRewardWeights pendulum() { return {}; }
  /// Seed eq. 23-28.
  static BalanceRewardWeights servos() { return {0.5, 0.1, 0.1, 0.05, 0.01, 0.005}; }

  /// Declares the options w_theta ... w_accel (balance_options.cpp).
  void declare_options(OptionTable& table);
};

/// r_t = 1 - (w_theta θ² + w_theta_dot θ̇² + w_p_dot ṗ² + w_a a² + w_s Δa² + w_accel (Δ²a)²)
/// with Δa_t = a_t - a_{t-1} and Δ²a_t = Δa_t - Δa_{t-1}; the action history is zero at
/// reset. `a` is a scalar: the ground velocity command (pendulum) or the action magnitude
/// (servos task).
class BalanceReward {
 public:
  explicit BalanceReward(const BalanceRewardWeights& weights = {}) : weights_(weights) {}

  /// Zeroes the action history (call at every reset).
  void reset() {
    previous_action_ = 0.0;
    previous_action_change_ = 0.0;
  }

  /// The reward of a step that applied `action` and led to the given state; updates the
  /// action history.
  /// @param pitch θ [rad]. @param pitch_rate θ̇ [rad/s]. @param ground_velocity ṗ [m/s].
  double operator()(double pitch, double pitch_rate, double ground_velocity, double action) {
    const double change = action - previous_action_;
    const double change_of_change = change - previous_action_change_;
    previous_action_ = action;
    previous_action_change_ = change;
    return 1.0 -
           (weights_.w_theta * pitch * pitch + weights_.w_theta_dot * pitch_rate * pitch_rate +
            weights_.w_p_dot * ground_velocity * ground_velocity + weights_.w_a * action * action +
            weights_.w_s * change * change +
            weights_.w_accel * change_of_change * change_of_change);
  }

  const BalanceRewardWeights& weights() const { return weights_; }

 private:
  BalanceRewardWeights weights_;
  double previous_action_ = 0.0;
  double previous_action_change_ = 0.0;
};

}  // namespace upkie_rl
