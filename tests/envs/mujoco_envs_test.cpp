/// The Upkie-MuJoCo-* ids: every kind, its options, the seed's PD check, determinism.

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "envs/registry/env_factory.hpp"

namespace upkie_rl {
namespace {

TEST(MujocoEnvs, EveryKindMakesAndSteps) {
  for (const char* id : {"Upkie-MuJoCo-Servos", "Upkie-MuJoCo-Pendulum", "Upkie-MuJoCo-Gyropod",
                         "Upkie-MuJoCo-ServosTask"}) {
    auto env = make_env(id);
    std::vector<float> observation(env->observation_space().size());
    std::vector<float> action(env->action_space().size());
    env->reset(0, observation);
    env->neutral_action(action);
    for (int step = 0; step < 20; ++step) env->step(action, observation);
    const Observation* full = env->full_observation();
    ASSERT_NE(full, nullptr) << id;
    EXPECT_TRUE(full->has_sim) << id;
    EXPECT_NEAR(full->time, 0.1, 1e-9) << id;
    EXPECT_EQ(env->physics_steps_per_step(), 5) << id;
  }
}

TEST(MujocoEnvs, PhysicsOptionsApply) {
  auto env = make_env("Upkie-MuJoCo-Pendulum",
                      {{"frequency", "100"}, {"nb_substeps", "10"}, {"inertia", "urdf"}});
  EXPECT_EQ(env->physics_steps_per_step(), 10);
  EXPECT_DOUBLE_EQ(env->timestep(), 0.01);
  EXPECT_THROW(make_env("Upkie-MuJoCo-Pendulum", {{"shm_name", "/x"}}), std::invalid_argument);
}

/// Length of an episode under ground velocity = 10 theta + p + 0.1 p_dot.
int pd_episode_length(Env& env, std::uint64_t seed, std::vector<float>* trajectory) {
  std::array<float, 4> observation{};
  env.reset(seed, observation);
  for (int length = 1;; ++length) {
    const std::array<float, 1> action{10.0f * observation[0] + observation[1] +
                                      0.1f * observation[3]};
    const StepResult result = env.step(action, observation);
    if (trajectory) trajectory->insert(trajectory->end(), observation.begin(), observation.end());
    if (result.terminated || result.truncated) return length;
  }
}

TEST(MujocoEnvs, PdLawBalancesThePendulumAndRunsAreDeterministic) {
  const EnvFactory factory =
      make_env_factory("Upkie-MuJoCo-Pendulum", {{"init_rand_pitch", "0.1"}});
  auto first = factory();
  auto second = factory();  // shares the compiled model
  std::vector<float> first_trajectory, second_trajectory;
  EXPECT_EQ(pd_episode_length(*first, 7, &first_trajectory), 300);
  EXPECT_EQ(pd_episode_length(*second, 7, &second_trajectory), 300);
  EXPECT_EQ(first_trajectory, second_trajectory);
}

}  // namespace
}  // namespace upkie_rl
