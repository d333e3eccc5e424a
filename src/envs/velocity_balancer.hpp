#pragma once
/// @file
/// VelocityBalancer: the classical baseline of the velocity task. Legs held at the default
/// pose; the wheels driven by the pendulum's linear balance law in error coordinates, so
/// that the robot balances while its ground velocity tracks the command, plus a
/// differential wheel speed for the yaw rate.

#include <array>

#include "envs/controller.hpp"
#include "envs/env.hpp"

namespace upkie_rl {

/// With θ the pitch (from the gravity vector of the observation), θ̇ the gyroscope's pitch
/// rate, ṗ = r(ω_left - ω_right)/2 the wheel odometry velocity, v* and ψ̇* the command,
/// v_ref a reference that ramps toward v* at 1 m/s², and e_p the integral of ṗ - v_ref
/// since reset (bounded to ±5 m):
///
///   ground velocity u = v_ref + k·[θ, e_p, θ̇, ṗ - v_ref]
///   ω_left = u/r - (track/2)/r·ψ̇*,  ω_right = -u/r - (track/2)/r·ψ̇*
///
/// written as the normalised wheel actions of the velocity task, legs at 0. The gains k are
/// the pendulum's (`linear:k1,k2,k3,k4`, or `lqr`: designed on the pendulum at the task's
/// rate).
class VelocityBalancer final : public Controller {
 public:
  /// @throws std::invalid_argument when `env` is not a velocity environment.
  VelocityBalancer(const Env& env, const std::array<float, 4>& gains);

  void reset() override {
    position_error_ = 0.0;
    reference_velocity_ = 0.0;
  }
  void act(std::span<const float> observation, std::span<float> action) override;

 private:
  std::array<float, 4> gains_;
  double wheel_radius_;
  double yaw_factor_;            ///< (track / 2) / r
  double wheel_velocity_scale_;  ///< rad/s at action 1
  double timestep_;
  double position_error_ = 0.0;      ///< ∫(ṗ - v_ref) dt [m]
  double reference_velocity_ = 0.0;  ///< v_ref, ramped toward v* at 1 m/s² [m/s]
};

}  // namespace upkie_rl
