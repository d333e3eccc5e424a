#include "envs/controllers/lqr_design.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "sim/random_draws.hpp"

namespace upkie_rl {
namespace {

constexpr std::array<const char*, 4> kStateNames = {"theta", "p", "theta_dot", "p_dot"};
constexpr double kMaxPitch = 0.3;  // [rad] samples beyond it are not "near upright"
constexpr int kEpisodeSteps = 300;
constexpr int kHoldSteps = 20;

std::size_t component(const BoxSpace& space, const char* name) {
  const std::size_t index = space.index_of(name);
  if (index == space.size()) {
    throw std::invalid_argument(
        std::string("LQR design: the environment has no \"") + name +
        "\" component (it needs theta, p, theta_dot, p_dot and ground_velocity: the pendulum "
        "or gyropod)");
  }
  return index;
}

/// Transitions of the balance state x = [θ, p, θ̇, ṗ] under a command u, near upright.
struct Transitions {
  std::vector<Eigen::Matrix<double, 5, 1>> inputs;  ///< [x; u]
  std::vector<Eigen::Vector4d> outputs;             ///< The next x.
};

/// Runs `episodes` episodes of `env` under a random piecewise-constant command of amplitude
/// `excitation`, and keeps the transitions until a fall.
Transitions collect_transitions(Env& env, std::uint64_t seed, int episodes, double excitation) {
  const BoxSpace& observation_space = env.observation_space();
  std::array<std::size_t, 4> state_index{};
  for (std::size_t k = 0; k < 4; ++k) state_index[k] = component(observation_space, kStateNames[k]);
  const std::size_t command_index = component(env.action_space(), "ground_velocity");
  const float low = env.action_space().low[command_index];
  const float high = env.action_space().high[command_index];

  std::vector<float> observation(observation_space.size());
  std::vector<float> action(env.action_space().size());
  Transitions transitions;
  std::mt19937_64 generator(seed);
  const auto state = [&] {
    Eigen::Vector4d x;
    for (std::size_t k = 0; k < 4; ++k) x[k] = observation[state_index[k]];
    return x;
  };
  for (int episode = 0; episode < episodes; ++episode) {
    env.reset(seed + static_cast<std::uint64_t>(episode), observation);
    double offset = 0.0;
    for (int step = 0; step < kEpisodeSteps; ++step) {
      const Eigen::Vector4d x = state();
      // Piecewise-constant excitation (changes every kHoldSteps): it excites the slow
      // balance dynamics rather than the legs' fast compliance.
      if (step % kHoldSteps == 0) offset = uniform_symmetric(generator, excitation);
      const double command = offset;
      env.neutral_action(action);
      action[command_index] = std::clamp(static_cast<float>(command), low, high);
      const StepResult result = env.step(action, observation);
      if (result.terminated || std::abs(x[0]) > kMaxPitch) break;
      Eigen::Matrix<double, 5, 1> input;
      input << x, static_cast<double>(action[command_index]);
      transitions.inputs.push_back(input);
      transitions.outputs.push_back(state());
      if (result.truncated) break;
    }
  }
  return transitions;
}

/// The least-squares linear dynamics of `transitions`.
/// @throws std::invalid_argument when they do not determine the dynamics.
BalanceLinearization fit_dynamics(const Transitions& transitions) {
  const std::vector<Eigen::Matrix<double, 5, 1>>& inputs = transitions.inputs;
  const auto samples = static_cast<Eigen::Index>(inputs.size());
  if (samples < 50) {
    throw std::invalid_argument("LQR design: only " + std::to_string(samples) +
                                " samples near upright; the dynamics are not determined");
  }
  // The position p enters no dynamics (the floor is the same everywhere): each next state
  // is regressed on [θ, θ̇, ṗ, u] only, p's row as an increment, which keeps correlations
  // of p with the other states in the data out of the model.
  constexpr std::array<int, 3> kDynamicStates = {0, 2, 3};
  Eigen::MatrixXd regressors(samples, 4);
  Eigen::MatrixXd targets(samples, 4);
  for (Eigen::Index i = 0; i < samples; ++i) {
    for (int j = 0; j < 3; ++j) regressors(i, j) = inputs[i][kDynamicStates[j]];
    regressors(i, 3) = inputs[i][4];
    targets.row(i) = transitions.outputs[i].transpose();
    targets(i, 1) -= inputs[i][1];
  }
  const LeastSquaresFit fit = fit_least_squares(regressors, targets, "LQR design");
  const Eigen::MatrixXd& solution = fit.solution;  // 4 x 4: rows θ, θ̇, ṗ, u
  BalanceLinearization result;
  result.A.setZero();
  for (int j = 0; j < 3; ++j) result.A.col(kDynamicStates[j]) = solution.row(j).transpose();
  result.A(1, 1) = 1.0;
  result.B = solution.row(3).transpose();
  result.rms_error = fit.rms_error;
  result.samples = static_cast<int>(samples);
  return result;
}

}  // namespace

BalanceLinearization identify_balance_dynamics(Env& env, std::uint64_t seed, int episodes,
                                               double excitation) {
  return fit_dynamics(collect_transitions(env, seed, episodes, excitation));
}

Eigen::MatrixXd bryson_cost(std::initializer_list<double> deviations, const std::string& context) {
  Eigen::MatrixXd cost = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(deviations.size()),
                                               static_cast<Eigen::Index>(deviations.size()));
  Eigen::Index k = 0;
  for (const double deviation : deviations) {
    if (!(deviation > 0.0)) throw std::invalid_argument(context + ": weights must be > 0");
    cost(k, k) = 1.0 / (deviation * deviation);
    ++k;
  }
  return cost;
}

LeastSquaresFit fit_least_squares(const Eigen::MatrixXd& regressors, const Eigen::MatrixXd& targets,
                                  const std::string& context) {
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(regressors);
  if (qr.rank() < regressors.cols()) {
    throw std::invalid_argument(context + ": the excitation does not determine the dynamics");
  }
  LeastSquaresFit fit;
  fit.solution = qr.solve(targets);
  const Eigen::MatrixXd residual = regressors * fit.solution - targets;
  fit.rms_error =
      (residual.colwise().squaredNorm() / static_cast<double>(regressors.rows())).cwiseSqrt();
  return fit;
}

Eigen::MatrixXd discrete_lqr_gain(const Eigen::MatrixXd& dynamics, const Eigen::MatrixXd& input,
                                  const Eigen::MatrixXd& state_cost,
                                  const Eigen::MatrixXd& input_cost) {
  // The textbook names: x' = A x + B u, cost xᵀQx + uᵀRu, cost-to-go P, gain K.
  const Eigen::MatrixXd& a = dynamics;
  const Eigen::MatrixXd& b = input;
  const Eigen::MatrixXd& q = state_cost;
  const Eigen::MatrixXd& r = input_cost;
  const Eigen::Index n = a.rows();
  if (a.cols() != n || b.rows() != n || q.rows() != n || q.cols() != n || r.rows() != b.cols() ||
      r.cols() != b.cols()) {
    throw std::invalid_argument("LQR: inconsistent matrix sizes");
  }
  if (!a.allFinite() || !b.allFinite() || !q.allFinite() || !r.allFinite()) {
    throw std::invalid_argument("LQR: non-finite matrix entries");
  }
  if (r.llt().info() != Eigen::Success)
    throw std::invalid_argument("LQR: R (input_cost) is not positive definite");
  constexpr int kMaxIterations = 100000;
  constexpr double kTolerance = 1e-11;
  Eigen::MatrixXd cost_to_go = q;
  Eigen::MatrixXd gain;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    gain = (r + b.transpose() * cost_to_go * b).ldlt().solve(b.transpose() * cost_to_go * a);
    Eigen::MatrixXd next = q + a.transpose() * cost_to_go * (a - b * gain);
    next = 0.5 * (next + next.transpose());
    if (!next.allFinite()) break;
    const double change = (next - cost_to_go).cwiseAbs().maxCoeff();
    cost_to_go = std::move(next);
    if (change <= kTolerance * std::max(1.0, cost_to_go.cwiseAbs().maxCoeff())) {
      return (r + b.transpose() * cost_to_go * b).ldlt().solve(b.transpose() * cost_to_go * a);
    }
  }
  throw std::invalid_argument(
      "LQR: the Riccati iteration does not converge (is (A, B) stabilisable?)");
}

std::array<float, 4> design_lqr_gains(Env& env, const LqrWeights& weights, std::uint64_t seed) {
  const BalanceLinearization model = identify_balance_dynamics(env, seed);
  const std::array<double, 4>& d = weights.max_state;
  const Eigen::MatrixXd state_cost = bryson_cost({d[0], d[1], d[2], d[3]}, "LQR");
  const Eigen::MatrixXd input_cost = bryson_cost({weights.max_command}, "LQR");
  const Eigen::MatrixXd gain = discrete_lqr_gain(model.A, model.B, state_cost, input_cost);
  std::array<float, 4> gains{};
  for (int k = 0; k < 4; ++k) gains[k] = static_cast<float>(-gain(0, k));
  return gains;
}

}  // namespace upkie_rl
