#pragma once
/// @file
/// PendulumEnv: Upkie as a wheeled inverted pendulum, the seed's task (section 1).

#include <memory>

#include "envs/kinds/ground_velocity_commander.hpp"
#include "envs/tasks/balance_task.hpp"
#include "envs/wrappers/servos_wrapper_env.hpp"

namespace upkie_rl {

/// Settings of PendulumEnv (the seed's defaults).
struct PendulumConfig {
  double max_ground_velocity = 1.0;  ///< a_max, the action bound [m/s].
  double leg_gain_scale = 1.0;       ///< Gain scales of the held legs.
  BalanceRewardWeights reward = BalanceRewardWeights::pendulum();
  BalanceTermination termination;

  /// Declares max_ground_velocity, leg_gain_scale, then the termination's and reward's.
  void declare_options(OptionTable& table);
};

/// Observation o = [θ, p, θ̇, ṗ] (pitch [rad], wheel odometry position [m], pitch rate
/// [rad/s], ground velocity [m/s]), action a = [ṗ*] in [-a_max, a_max] [m/s] (clamped).
/// Reward: seed eq. 9; terminations: seed section 1.5, checked after every step (p0 is the
/// position at reset). Truncation at 300 steps is the TimeLimit the registry adds.
class PendulumEnv final : public ServosWrapperEnv {
 public:
  PendulumEnv(std::unique_ptr<ServosEnv> servos, const PendulumConfig& config = {});

  /// The condition that ended the last step's episode (kNone while running).
  BalanceTermination::Reason termination_reason() const { return task_.termination_reason(); }
  const PendulumConfig& config() const { return config_; }

  void reset(std::optional<std::uint64_t> seed, std::span<float> observation) override;
  StepResult step(std::span<const float> action, std::span<float> observation) override;

 private:
  void write_observation(const Observation& full, std::span<float> observation) const;

  PendulumConfig config_;
  GroundVelocityCommander commander_;
  BalanceTask task_;
};

}  // namespace upkie_rl
