#pragma once
/// @file
/// BalanceTask: the seed's reward and termination wrapper (pendulum section 1.4-1.5,
/// servos section 4.4-4.5), computed from the full observation after each step.

#include "envs/core/env.hpp"
#include "envs/tasks/balance_reward.hpp"
#include "envs/tasks/balance_termination.hpp"
#include "sim/observation.hpp"

namespace upkie_rl {

/// Reads θ (`base_orientation.pitch`), θ̇ (`base_orientation.angular_velocity[1]`), p and ṗ
/// (`wheel_odometry`) from the observation; rewards with BalanceReward and terminates with
/// BalanceTermination on the drift from the position at reset.
class BalanceTask {
 public:
  BalanceTask(const BalanceRewardWeights& weights, const BalanceTermination& termination)
      : reward_(weights), termination_(termination) {}

  /// Records p0 and zeroes the action history.
  void reset(const Observation& observation) {
    reward_.reset();
    initial_position_ = observation.wheel_odometry.position;
    reason_ = BalanceTermination::Reason::kNone;
  }

  /// Reward and termination of a step that applied the scalar action `action` (ground
  /// velocity, or action magnitude) and led to `observation`.
  StepResult evaluate(const Observation& observation, double action) {
    const double pitch = observation.base_orientation.pitch;
    const double pitch_rate = observation.base_orientation.angular_velocity.y();
    const double velocity = observation.wheel_odometry.velocity;
    const double drift = observation.wheel_odometry.position - initial_position_;
    StepResult result;
    result.reward = reward_(pitch, pitch_rate, velocity, action);
    reason_ = termination_.check(pitch, drift, pitch_rate, velocity);
    result.terminated = reason_ != BalanceTermination::Reason::kNone;
    return result;
  }

  /// The condition that ended the episode at the last step (kNone while running).
  BalanceTermination::Reason termination_reason() const { return reason_; }

 private:
  BalanceReward reward_;
  BalanceTermination termination_;
  double initial_position_ = 0.0;
  BalanceTermination::Reason reason_ = BalanceTermination::Reason::kNone;
};

}  // namespace upkie_rl
