#pragma once
/// @file
/// The built-in controllers: `zero` and `linear:k1,k2,k3,k4`.

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "envs/controllers/controller.hpp"
#include "envs/core/env.hpp"

namespace upkie_rl {

/// Always the environment's neutral action (zero; the neutral servo commands for servos).
class ZeroController final : public Controller {
 public:
  explicit ZeroController(const Env& env);
  void act(std::span<const float> observation, std::span<float> action) override;

 private:
  std::vector<float> neutral_;
};

/// Ground velocity = k · [θ, p, θ̇, ṗ] [m/s], clamped to the action bounds; other action
/// components (the gyropod's yaw velocity) zero. Finds θ, p, θ̇, ṗ and the ground velocity
/// by component name ("theta", "p", "theta_dot", "p_dot", "ground_velocity"), so it drives
/// both the pendulum and the gyropod.
class LinearController final : public Controller {
 public:
  /// @throws std::invalid_argument when the environment lacks one of the named components.
  LinearController(const Env& env, const std::array<float, 4>& gains);
  void act(std::span<const float> observation, std::span<float> action) override;

 private:
  std::array<float, 4> gains_;
  std::array<std::size_t, 4> indices_{};
  std::size_t action_index_ = 0;
  float low_ = 0.0f;
  float high_ = 0.0f;
};

/// "zero", "linear:k1,k2,k3,k4" (see resolve_controller_spec for "lqr") or, on a velocity
/// task (Upkie-*-Velocity), "balancer:" and the eight numbers of VelocityBalancerGains. On
/// a velocity task the linear law is a VelocityBalancer without feedforward.
/// @throws std::invalid_argument naming the spec and listing the valid ones.
std::unique_ptr<Controller> make_builtin_controller(const std::string& spec, const Env& env);

/// Makes an environment to design a controller on.
using DesignEnvFactory = std::function<std::unique_ptr<Env>()>;

/// Turns a spec that needs a design into the linear law it designs: "lqr" or
/// "lqr:θmax,pmax,θ̇max,ṗmax,umax" (Bryson weights, envs/controllers/lqr_design.hpp) becomes
/// "linear:k1,k2,k3,k4" designed on an environment of `design_env`; on a velocity task it
/// becomes "balancer:..." designed by envs/controllers/velocity_balancer_design.hpp (the deviations
/// then bound the pitch, the integral of the velocity error, the pitch rate, the velocity
/// error and the command); other specs pass unchanged.
/// @throws std::invalid_argument on malformed weights or a failed design.
std::string resolve_controller_spec(const std::string& spec, const DesignEnvFactory& design_env);

}  // namespace upkie_rl
