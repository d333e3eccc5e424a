/// Upkie-Spine-Pendulum end to end: the environment drives a spine server (in-process, on
/// request, Bullet behind it) through shared memory.

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <thread>

#include "envs/registry/env_factory.hpp"
#include "sim/bullet_simulation.hpp"
#include "spine/spine_server.hpp"

namespace upkie_rl {
namespace {

TEST(SpinePendulum, LinearControllerBalancesThroughTheSpine) {
  const std::string shm_name = "/upkie-rl-envs-test-" + std::to_string(::getpid());
  BulletSimulation simulation(RobotModel::default_model());
  SpineServerConfig config;
  config.shm_name = shm_name;
  config.real_time = false;  // One simulation step (5 physics steps) per action.
  SpineServer server(simulation, config);
  std::atomic<bool> interrupt{false};
  std::thread spine([&] { server.run(interrupt); });

  int length = 0;
  bool terminated = false, truncated = false;
  {
    auto env = make_env("Upkie-Spine-Pendulum", {{"shm_name", shm_name},
                                                 {"regulate_frequency", "false"},
                                                 {"open_tries", "3"},
                                                 {"request_timeout", "5"}});
    std::array<float, 4> observation{};
    env->reset(0, observation);
    while (!terminated && !truncated) {
      const float velocity = 10.0f * observation[0] + 1.0f * observation[1] + 0.1f * observation[3];
      const std::array<float, 1> action{velocity};
      const StepResult result = env->step(action, observation);
      terminated = result.terminated;
      truncated = result.truncated;
      ++length;
    }
    ASSERT_NE(env->full_observation(), nullptr);
    EXPECT_NEAR(env->full_observation()->base_orientation.pitch, 0.0, 0.2);
  }
  interrupt = true;
  spine.join();
  EXPECT_EQ(length, 300);
  EXPECT_TRUE(truncated);
  EXPECT_FALSE(terminated);
  EXPECT_EQ(server.error(), "");
}

}  // namespace
}  // namespace upkie_rl
