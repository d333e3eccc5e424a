/// ServosEnv::push_base: the pushes a browser gives in `upkie-rl drive`.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

#include "envs/kinds/velocity_env.hpp"
#include "envs/registry/env_factory.hpp"

namespace upkie_rl {
namespace {

/// Base x [m] after 20 steps of zero actions from a reset, pushed by `force` at the start.
double base_x_after_push(const Eigen::Vector3d& force) {
  std::unique_ptr<Env> env = make_env("Upkie-MuJoCo-Velocity", {});
  std::vector<float> observation(env->observation_space().size());
  std::vector<float> action(env->action_space().size(), 0.0f);
  env->reset(0, observation);
  EXPECT_TRUE(find_velocity_env(*env)->servos().push_base(force, 0.2));
  for (int step = 0; step < 20; ++step) env->step(action, observation);
  return env->full_observation()->sim_base.position.x();
}

TEST(HandPush, MovesTheBaseTheWayItPushes) {
  const double still = base_x_after_push(Eigen::Vector3d::Zero());
  EXPECT_GT(base_x_after_push({30.0, 0.0, 0.0}), still + 0.01);
  EXPECT_LT(base_x_after_push({-30.0, 0.0, 0.0}), still - 0.01);
}

TEST(HandPush, RefusesBadPushesAndDoesNothingWithoutPhysics) {
  std::unique_ptr<Env> mujoco = make_env("Upkie-MuJoCo-Velocity", {});
  ServosEnv& servos = find_velocity_env(*mujoco)->servos();
  EXPECT_THROW(servos.push_base({std::nan(""), 0.0, 0.0}, 0.2), std::invalid_argument);
  EXPECT_THROW(servos.push_base({1.0, 0.0, 0.0}, 0.0), std::invalid_argument);
  std::unique_ptr<Env> mock = make_env("Upkie-Mock-Velocity", {});
  EXPECT_FALSE(find_velocity_env(*mock)->servos().push_base({1.0, 0.0, 0.0}, 0.2));
}

}  // namespace
}  // namespace upkie_rl
