#pragma once
/// @file
/// ServosTaskEnv: the seed's full-model servos task (section 4), the wrapper chain
/// reward/termination -> Box[-1,1]^6 actions -> 12-D observations on ServosEnv.

#include <memory>

#include "envs/tasks/balance_task.hpp"
#include "envs/wrappers/servos_wrapper_env.hpp"

namespace upkie_rl {

/// Settings of ServosTaskEnv. The defaults are the seed's task; the options after the gains
/// make it learnable (docs/training.md, "Full servos that balance").
struct ServosTaskConfig {
  /// How the |a| of the reward measures an action.
  enum class ActionMagnitude {
    kServo,       ///< Σ|wheel velocity command [rad/s]| + Σ|leg position command [rad]| (seed).
    kNormalized,  ///< Mean |u_i| of the normalised action, in [0, 1].
  };

  BalanceRewardWeights reward = BalanceRewardWeights::servos();
  BalanceTermination termination;
  double wheel_kp_scale = 0.0;  ///< Seed section 4.2.
  double wheel_kd_scale = 1.7;
  double leg_kp_scale = 2.0;
  double leg_kd_scale = 1.7;
  /// Appends the base pitch [rad] and pitch rate [rad/s], what the robot's IMU gives, to
  /// the 12 joint components (the seed's observation has no base orientation).
  bool observe_pitch = false;
  ActionMagnitude action_magnitude = ActionMagnitude::kServo;
  /// Wheel velocity command at u = ±1 [rad/s]; 0 for the joint's velocity limit (seed).
  double max_wheel_velocity = 0.0;
  /// Fraction of each leg joint's range that u in [-1, 1] spans, centred on the middle of
  /// the range (1: the whole range, the seed's mapping).
  double leg_action_scale = 1.0;

  /// Declares the termination's and reward's options, then observe_pitch,
  /// action_magnitude, max_wheel_velocity and leg_action_scale.
  void declare_options(OptionTable& table);
};

/// Action u in [-1, 1]^6, one per joint in the standard order. Wheels: velocity =
/// u·max_wheel_velocity (the velocity limit by default), position NaN, gains (wheel_kp_scale,
/// wheel_kd_scale). Legs: position = leg_action_scale·u mapped linearly onto [lower, upper],
/// velocity 0, gains (leg_kp_scale, leg_kd_scale). Feedforward torque 0 and maximum torque = effort
/// for all.
///
/// Observation: (position [rad], velocity [rad/s]) of each joint, 12 components, then
/// `base.pitch` and `base.pitch_rate` with observe_pitch.
///
/// Reward (seed eq. 22) on θ, θ̇, ṗ from the full observation and the action magnitude
/// |a| (ServosTaskConfig::ActionMagnitude); terminations as the pendulum. The 300-step truncation
/// is the TimeLimit the registry adds.
class ServosTaskEnv final : public ServosWrapperEnv {
 public:
  ServosTaskEnv(std::unique_ptr<ServosEnv> servos, const ServosTaskConfig& config = {});

  /// The servo commands `normalized` maps to.
  void servo_action_from_normalized(std::span<const float> normalized, ServoAction& action) const;

  /// Σ|wheel velocity| + Σ|leg position| of `action` (the seed's |a| of eq. 22).
  static double action_magnitude(const ServoAction& action);
  /// Mean |u_i| of a normalised action.
  static double normalized_action_magnitude(std::span<const float> normalized);

  BalanceTermination::Reason termination_reason() const { return task_.termination_reason(); }

  void reset(std::optional<std::uint64_t> seed, std::span<float> observation) override;
  StepResult step(std::span<const float> action, std::span<float> observation) override;

 private:
  void write_observation(const Observation& full, std::span<float> observation) const;

  ServosTaskConfig config_;
  BalanceTask task_;
  std::array<double, kNumServos> wheel_velocity_scale_{};  ///< u = 1 in rad/s, wheels only.
  std::array<float, kNumServos> clamped_{};
  ServoAction servo_action_{};
};

}  // namespace upkie_rl
