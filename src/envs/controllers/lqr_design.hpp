#pragma once
/// @file
/// LQR balance controllers designed on our own simulation: the discrete-time dynamics of
/// [θ, p, θ̇, ṗ] under the ground-velocity command are identified by least squares from
/// episodes near upright, then the discrete algebraic Riccati equation gives the gains.

#include <array>
#include <cstdint>
#include <initializer_list>
#include <string>

#include <Eigen/Core>

#include "envs/core/env.hpp"

namespace upkie_rl {

/// x_{k+1} = A x_k + B u_k for x = [θ, p, θ̇, ṗ] and u the ground velocity command, one agent
/// step apart.
struct BalanceLinearization {
  Eigen::Matrix4d A = Eigen::Matrix4d::Identity();
  Eigen::Vector4d B = Eigen::Vector4d::Zero();
  /// Root-mean-square one-step prediction error of each state component.
  Eigen::Vector4d rms_error = Eigen::Vector4d::Zero();
  int samples = 0;
};

/// Identifies the balance dynamics of `env` (a pendulum or gyropod: components named
/// theta, p, theta_dot, p_dot and ground_velocity) by least squares from `episodes`
/// open-loop episodes: ground velocity commands drawn in ±excitation m/s and held for 20
/// steps, samples kept while |θ| < 0.3 rad (the robot falls within a second). Open loop,
/// because feedback would correlate the command with the state and confound their
/// effects. Deterministic given `seed`.
/// @throws std::invalid_argument when the environment lacks a component or the data do
///         not determine the dynamics.
BalanceLinearization identify_balance_dynamics(Env& env, std::uint64_t seed, int episodes = 20,
                                               double excitation = 0.5);

/// The gain K of u = -K x minimising Σ xᵀQx + uᵀRu for x_{k+1} = A x + B u (discrete
/// algebraic Riccati equation solved by fixed-point iteration), with A = dynamics,
/// B = input, Q = state_cost, R = input_cost.
/// @throws std::invalid_argument when the iteration does not converge (an uncontrollable
///         or unstabilisable pair) or the inputs are not finite and symmetric positive.
Eigen::MatrixXd discrete_lqr_gain(const Eigen::MatrixXd& dynamics, const Eigen::MatrixXd& input,
                                  const Eigen::MatrixXd& state_cost,
                                  const Eigen::MatrixXd& input_cost);

/// Bryson's rule: the diagonal cost 1/d² of each largest acceptable deviation d.
/// @throws std::invalid_argument "<context>: weights must be > 0" on a d that is not.
Eigen::MatrixXd bryson_cost(std::initializer_list<double> deviations, const std::string& context);

/// A least-squares fit of targets (one column each) on regressors (one row per sample).
struct LeastSquaresFit {
  Eigen::MatrixXd solution;   ///< regressors × solution ≈ targets.
  Eigen::VectorXd rms_error;  ///< Root-mean-square residual of each target column.
};

/// Fits `targets` on `regressors` (column-pivoting QR).
/// @throws std::invalid_argument "<context>: the excitation does not determine the dynamics"
///         when the regressors do not have full column rank.
LeastSquaresFit fit_least_squares(const Eigen::MatrixXd& regressors, const Eigen::MatrixXd& targets,
                                  const std::string& context);

/// Weights of the balance LQR, as Bryson's rule: the largest acceptable deviation of each
/// state and of the command. Defaults: 0.1 rad, 1 m, 1 rad/s, 0.5 m/s, 1 m/s.
struct LqrWeights {
  std::array<double, 4> max_state{0.1, 1.0, 1.0, 0.5};
  double max_command = 1.0;
};

/// Gains k of the law ground velocity = k·[θ, p, θ̇, ṗ] (k = -K), designed on `env`.
std::array<float, 4> design_lqr_gains(Env& env, const LqrWeights& weights = {},
                                      std::uint64_t seed = 0);

}  // namespace upkie_rl
