#pragma once
/// @file
/// Designs the velocity task's classical baseline (VelocityBalancer) on the environment
/// itself: a linear model of the balance dynamics of the robot driving at the commanded
/// speeds is identified by least squares, then an LQR with an integral state gives the
/// feedback gains and the model's steady states the feedforward.

#include <cstdint>

#include <Eigen/Core>

#include "envs/controllers/velocity_balancer.hpp"
#include "envs/core/env.hpp"

namespace upkie_rl {

/// x_{k+1} = A x_k + B u_k + c for x = [θ, θ̇, v̂] (pitch, pitch rate, filtered wheel
/// odometry velocity as VelocityBalancer computes them) and u the ground velocity command,
/// one agent step apart.
struct VelocityBalanceModel {
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  Eigen::Vector3d B = Eigen::Vector3d::Zero();
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  /// Root-mean-square one-step prediction error of each state component.
  Eigen::Vector3d rms_error = Eigen::Vector3d::Zero();
  int samples = 0;
};

/// Bryson weights of the design: the largest acceptable deviation of each state and of the
/// command. Defaults: 0.1 rad, 1 rad/s, 0.2 m/s, 0.5 m, 1 m/s.
struct VelocityBalancerWeights {
  double max_pitch = 0.1;
  double max_pitch_rate = 1.0;
  double max_velocity_error = 0.2;
  double max_position_error = 0.5;
  double max_command = 1.0;
};

/// Identifies the model from `episodes` episodes of 500 steps of `env` (a velocity task,
/// nominal conditions) driven by `law` with forward commands drawn in ±max_reference and
/// held 2 s, and a ground velocity excitation drawn in ±0.3 m/s and held 5 steps. Closed
/// loop, so that the robot stays up while it drives: the excitation keeps the command
/// from being a function of the state. Samples are kept while |θ| < 0.3 rad.
/// Deterministic given `seed`.
/// @throws std::invalid_argument when `env` is not a velocity task or the data do not
///         determine the model.
VelocityBalanceModel identify_velocity_balance(Env& env, const VelocityBalancerGains& law,
                                               double max_reference, std::uint64_t seed,
                                               int episodes);

/// The balancer for `model`: feedback gains of the discrete LQR on [θ, θ̇, v̂ - v_ref, e]
/// (e' = e + dt·(v̂ - v_ref)), feedforward from the model's steady states at constant
/// velocity (θ̇ = 0, v̂ = v_ref) and at constant acceleration (θ̇ = 0, v̂ growing by a·dt
/// per step).
/// @throws std::invalid_argument on non-positive weights or an unstabilisable model.
VelocityBalancerGains velocity_balancer_for(const VelocityBalanceModel& model, double timestep,
                                            const VelocityBalancerWeights& weights);

/// Designs the balancer on `env` in two rounds: a model identified standing (driven by a
/// hand-set stabilising law) gives a first design, which then drives the robot at speeds
/// up to 0.8 m/s for the final model.
VelocityBalancerGains design_velocity_balancer(Env& env,
                                               const VelocityBalancerWeights& weights = {},
                                               std::uint64_t seed = 0);

}  // namespace upkie_rl
