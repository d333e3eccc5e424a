#pragma once
/// @file
/// GyropodEnv: Upkie as a gyropod, balancing and turning on its wheels (public Upkie).

#include <memory>

#include "envs/kinds/ground_velocity_commander.hpp"
#include "envs/wrappers/servos_wrapper_env.hpp"

namespace upkie_rl {

/// Settings of GyropodEnv (public Upkie defaults).
struct GyropodConfig {
  double max_ground_velocity = 3.0;  ///< Bound of ṗ* [m/s].
  double max_yaw_velocity = 1.0;     ///< Bound of ψ̇* [rad/s].
  double fall_pitch = 1.0;           ///< |θ| above it terminates [rad].
  double leg_gain_scale = 1.0;       ///< Gain scales of the held legs.

  /// Declares the options of the fields, by their names.
  void declare_options(OptionTable& table);
};

/// Observation [p, θ, ψ, ṗ, θ̇, ψ̇] (m, rad, rad, m/s, rad/s, rad/s), action [ṗ*, ψ̇*]
/// clamped to ±[max_ground_velocity, max_yaw_velocity]. ψ integrates the commanded yaw
/// rate (zero at reset) and ψ̇ is the last command. Reward 1 per step (survival);
/// terminated when |θ| > fall_pitch after a step.
class GyropodEnv final : public ServosWrapperEnv {
 public:
  GyropodEnv(std::unique_ptr<ServosEnv> servos, const GyropodConfig& config = {});

  void reset(std::optional<std::uint64_t> seed, std::span<float> observation) override;
  StepResult step(std::span<const float> action, std::span<float> observation) override;

 private:
  void write_observation(const Observation& full, std::span<float> observation) const;

  GyropodConfig config_;
  GroundVelocityCommander commander_;
  double yaw_ = 0.0;           // ψ [rad]
  double yaw_velocity_ = 0.0;  // ψ̇, the last command [rad/s]
};

}  // namespace upkie_rl
