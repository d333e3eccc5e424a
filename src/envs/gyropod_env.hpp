#pragma once
/// @file
/// GyropodEnv: Upkie as a gyropod, balancing and turning on its wheels (public Upkie).

#include <memory>

#include "envs/ground_velocity_commander.hpp"
#include "envs/servos_env.hpp"

namespace upkie_rl {

/// Settings of GyropodEnv (public Upkie defaults).
struct GyropodConfig {
  double max_ground_velocity = 3.0;  ///< Bound of ṗ* [m/s].
  double max_yaw_velocity = 1.0;     ///< Bound of ψ̇* [rad/s].
  double fall_pitch = 1.0;           ///< |θ| above it terminates [rad].
  double leg_gain_scale = 1.0;       ///< Gain scales of the held legs.
};

/// Observation [p, θ, ψ, ṗ, θ̇, ψ̇] (m, rad, rad, m/s, rad/s, rad/s), action [ṗ*, ψ̇*]
/// clamped to ±[max_ground_velocity, max_yaw_velocity]. ψ integrates the commanded yaw
/// rate (zero at reset) and ψ̇ is the last command. Reward 1 per step (survival);
/// terminated when |θ| > fall_pitch after a step.
class GyropodEnv final : public Env {
 public:
  GyropodEnv(std::unique_ptr<ServosEnv> servos, const GyropodConfig& config = {});

  ServosEnv& servos() { return *servos_; }

  const BoxSpace& observation_space() const override { return observation_space_; }
  const BoxSpace& action_space() const override { return action_space_; }
  void reset(std::optional<std::uint64_t> seed, std::span<float> observation) override;
  StepResult step(std::span<const float> action, std::span<float> observation) override;
  const Observation* full_observation() const override { return servos_->full_observation(); }
  double timestep() const override { return servos_->timestep(); }
  int physics_steps_per_step() const override { return servos_->physics_steps_per_step(); }

 private:
  void write_observation(const Observation& full, std::span<float> observation) const;

  std::unique_ptr<ServosEnv> servos_;
  GyropodConfig config_;
  BoxSpace observation_space_;
  BoxSpace action_space_;
  GroundVelocityCommander commander_;
  double yaw_ = 0.0;           // ψ [rad]
  double yaw_velocity_ = 0.0;  // ψ̇, the last command [rad/s]
};

}  // namespace upkie_rl
