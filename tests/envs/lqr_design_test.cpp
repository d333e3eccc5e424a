/// LQR design: the Riccati solver against hand-checked cases, the identification on our
/// simulation, and the designed law balancing 10 s on both engines.

#include "envs/controllers/lqr_design.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>

#include "envs/controllers/builtin_controllers.hpp"
#include "envs/registry/env_factory.hpp"

namespace upkie_rl {
namespace {

TEST(DiscreteLqr, ScalarCaseMatchesTheHandSolution) {
  // x' = x + u, Q = R = 1: P = 1 + P - P²/(1 + P) gives P² - P - 1 = 0, P = (1 + √5)/2,
  // and K = P / (1 + P) = (√5 - 1)/2 = 0.6180...
  Eigen::MatrixXd one = Eigen::MatrixXd::Ones(1, 1);
  const Eigen::MatrixXd K = discrete_lqr_gain(one, one, one, one);
  EXPECT_NEAR(K(0, 0), (std::sqrt(5.0) - 1.0) / 2.0, 1e-9);
}

TEST(DiscreteLqr, GainStabilisesAnUnstableSystem) {
  // A discretised double integrator (dt = 0.1) with an unstable drift term.
  Eigen::MatrixXd A(2, 2), B(2, 1), Q = Eigen::MatrixXd::Identity(2, 2), R(1, 1);
  A << 1.0, 0.1, 0.2, 1.05;
  B << 0.005, 0.1;
  R << 0.5;
  const Eigen::MatrixXd K = discrete_lqr_gain(A, B, Q, R);
  const Eigen::MatrixXd closed = A - B * K;
  const Eigen::VectorXcd eigenvalues = closed.eigenvalues();
  for (Eigen::Index i = 0; i < eigenvalues.size(); ++i) EXPECT_LT(std::abs(eigenvalues[i]), 1.0);
  EXPECT_GT(A.eigenvalues().cwiseAbs().maxCoeff(), 1.0);  // the open loop is unstable
}

TEST(DiscreteLqr, UnstabilisablePairIsRefused) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Identity(2, 2) * 1.2;
  Eigen::MatrixXd B(2, 1);
  B << 1.0, 0.0;  // the second state, unstable, cannot be reached
  EXPECT_THROW(
      discrete_lqr_gain(A, B, Eigen::MatrixXd::Identity(2, 2), Eigen::MatrixXd::Ones(1, 1)),
      std::invalid_argument);
  EXPECT_THROW(
      discrete_lqr_gain(A, B, Eigen::MatrixXd::Identity(3, 3), Eigen::MatrixXd::Ones(1, 1)),
      std::invalid_argument);
}

class LqrOnEngine : public ::testing::TestWithParam<const char*> {};

TEST_P(LqrOnEngine, IdentifiedModelIsAnInvertedPendulum) {
  auto env = make_env(std::string("Upkie-") + GetParam() + "-Pendulum");
  const BalanceLinearization model = identify_balance_dynamics(*env, 0);
  EXPECT_GT(model.samples, 1000);
  EXPECT_NEAR(model.A(0, 2), env->timestep(), 0.2 * env->timestep());  // θ integrates θ̇
  EXPECT_GT(model.A(2, 0), 0.0);  // gravity: leaning forward speeds the fall forward
  EXPECT_GT(model.B(3), 0.5);     // the wheels follow the ground velocity command
  EXPECT_EQ(model.A(1, 1), 1.0);  // nothing depends on the position
}

TEST_P(LqrOnEngine, DesignedLawBalancesTenSeconds) {
  for (const char* kind : {"Pendulum", "Gyropod"}) {
    const std::string id = std::string("Upkie-") + GetParam() + "-" + kind;
    const std::string spec = resolve_controller_spec("lqr", [&id] { return make_env(id); });
    ASSERT_EQ(spec.rfind("linear:", 0), 0u) << spec;
    auto env = make_env(id, {{"max_episode_steps", "2000"}, {"init_rand_pitch", "0.1"}});
    auto controller = make_builtin_controller(spec, *env);
    std::vector<float> observation(env->observation_space().size());
    std::vector<float> action(env->action_space().size());
    const std::size_t theta = env->observation_space().index_of("theta");
    for (std::uint64_t seed = 0; seed < 3; ++seed) {
      env->reset(seed, observation);
      int steps = 0;
      for (; steps < 2000; ++steps) {
        controller->act(observation, action);
        const StepResult result = env->step(action, observation);
        ASSERT_FALSE(result.terminated) << id << " fell at step " << steps << " of seed " << seed;
        if (result.truncated) break;
      }
      EXPECT_EQ(steps, 1999) << id;
      EXPECT_LT(std::abs(observation[theta]), 0.05) << id;  // upright at the end
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Engines, LqrOnEngine, ::testing::Values("Bullet", "MuJoCo"));

TEST(LqrSpec, MalformedWeightsAndEnvironmentsWithoutPitchAreRefused) {
  const auto design = [] { return make_env("Upkie-MuJoCo-Pendulum"); };
  EXPECT_THROW(resolve_controller_spec("lqr:1,2,3", design), std::invalid_argument);
  EXPECT_THROW(resolve_controller_spec("lqr:0.1,1,1,0.5,-1", design), std::invalid_argument);
  EXPECT_THROW(resolve_controller_spec("lqr", [] { return make_env("Upkie-MuJoCo-Servos"); }),
               std::invalid_argument);
  EXPECT_EQ(resolve_controller_spec("linear:1,2,3,4", {}), "linear:1,2,3,4");
}

}  // namespace
}  // namespace upkie_rl
