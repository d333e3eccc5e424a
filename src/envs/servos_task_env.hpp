#pragma once
/// @file
/// ServosTaskEnv: the seed's full-model servos task (section 4), the wrapper chain
/// reward/termination -> Box[-1,1]^6 actions -> 12-D observations on ServosEnv.

#include <memory>

#include "envs/balance_task.hpp"
#include "envs/servos_wrapper_env.hpp"

namespace upkie_rl {

/// Settings of ServosTaskEnv (the seed's defaults).
struct ServosTaskConfig {
  BalanceRewardWeights reward = BalanceRewardWeights::servos();
  BalanceTermination termination;
  double wheel_kp_scale = 0.0;  ///< Seed section 4.2.
  double wheel_kd_scale = 1.7;
  double leg_kp_scale = 2.0;
  double leg_kd_scale = 1.7;
};

/// Action u in [-1, 1]^6, one per joint in the standard order. Wheels: velocity =
/// u·(velocity limit), position NaN, gains (wheel_kp_scale, wheel_kd_scale). Legs: position
/// = u mapped linearly onto [lower, upper], velocity 0, gains (leg_kp_scale, leg_kd_scale).
/// Feedforward torque 0 and maximum torque = effort for all.
///
/// Observation: (position [rad], velocity [rad/s]) of each joint, 12 components.
///
/// Reward (seed eq. 22) on θ, θ̇, ṗ from the full observation and the action magnitude
/// |a| = Σ|wheel velocity command| + Σ|leg position command| of the servo action;
/// terminations as the pendulum. The 300-step truncation is the TimeLimit the registry adds.
class ServosTaskEnv final : public ServosWrapperEnv {
 public:
  ServosTaskEnv(std::unique_ptr<ServosEnv> servos, const ServosTaskConfig& config = {});

  /// The servo commands `normalized` maps to.
  void servo_action_from_normalized(std::span<const float> normalized, ServoAction& action) const;

  /// Σ|wheel velocity| + Σ|leg position| of `action` (the |a| of eq. 22).
  static double action_magnitude(const ServoAction& action);

  BalanceTermination::Reason termination_reason() const { return task_.termination_reason(); }

  void reset(std::optional<std::uint64_t> seed, std::span<float> observation) override;
  StepResult step(std::span<const float> action, std::span<float> observation) override;

 private:
  void write_observation(const Observation& full, std::span<float> observation) const;

  ServosTaskConfig config_;
  BalanceTask task_;
  std::array<float, kNumServos> clamped_{};
  ServoAction servo_action_{};
};

}  // namespace upkie_rl
