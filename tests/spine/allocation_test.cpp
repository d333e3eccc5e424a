// The spine link's per-step paths allocate nothing once warmed up: the agent's step
// (pack the action, wait, decode the observation) and the server's Action cycle (decode,
// merge into the action dictionary, step, write the observation).

#include <gtest/gtest.h>

#include "common/allocation_counter.hpp"

#include <atomic>
#include <thread>

#include "fake_simulation.hpp"
#include "spine/reset_config.hpp"
#include "spine/servo_action_message.hpp"
#include "spine/spine_backend.hpp"
#include "spine/spine_server.hpp"

namespace upkie_rl {
namespace {

ServoAction moving_action(int step) {
  ServoAction action = spine_default_servo_action();
  action[kLeftWheel].velocity = 0.01 * step;
  action[kRightWheel].velocity = -0.01 * step;
  return action;
}

TEST(SpineAllocations, ServerActionCycle) {
  testing::FakeSimulation simulation;
  SpineServerConfig config;
  config.shm_name = testing::unique_shm_name("alloc_server");
  config.real_time = false;
  SpineServer server(simulation, config);
  SharedMemory agent = SharedMemory::open(config.shm_name);
  msgpack::sbuffer message;
  write_start_config_msgpack(ResetState{}, {}, message);
  agent.write_payload({message.data(), message.size()});
  agent.set_request(Request::kStart);
  for (int i = 0; i < 6; ++i) server.cycle();
  ASSERT_EQ(server.state(), SpineState::kIdle);
  simulation.actions.reserve(100);  // the fake's own records must not count
  simulation.action_times.reserve(100);

  long during_steps = 0;
  for (int step = 0; step < 50; ++step) {
    write_servo_action_msgpack(moving_action(step), message);
    agent.write_payload({message.data(), message.size()});
    agent.set_request(Request::kAction);
    const std::size_t before = testing::this_thread_allocations;
    server.cycle();
    if (step >= 5) {  // warm-up: buffers grow to their working size
      during_steps += static_cast<long>(testing::this_thread_allocations - before);
    }
    ASSERT_EQ(agent.request(), 0u);
  }
  EXPECT_EQ(during_steps, 0);
  EXPECT_DOUBLE_EQ(simulation.actions.back()[kLeftWheel].velocity, 0.49);
}

/// Allocations of 45 backend steps after 5 of warm-up, against a spine on request or in
/// real time (then with a paced agent at 500 Hz, which sends each action twice).
long backend_step_allocations(bool real_time) {
  testing::FakeSimulation simulation;
  SpineServerConfig server_config;
  server_config.shm_name = testing::unique_shm_name("alloc_backend");
  server_config.real_time = real_time;
  SpineServer server(simulation, server_config);
  std::atomic<bool> interrupt{false};
  std::thread spine([&] { server.run(interrupt); });

  SpineBackendConfig config;
  config.shm_name = server_config.shm_name;
  config.regulate_frequency = real_time;
  config.agent_frequency = 500.0;
  config.open_tries = 1;
  long during_steps = 0;
  {
    SpineBackend backend(config);
    backend.reset(ResetState{});
    for (int step = 0; step < 50; ++step) {
      const ServoAction action = moving_action(step);
      const std::size_t before = testing::this_thread_allocations;
      backend.step(action);
      if (step >= 5) during_steps += static_cast<long>(testing::this_thread_allocations - before);
    }
    if (!real_time) EXPECT_NEAR(backend.observation().time, 50 * 0.005, 1e-12);
  }
  interrupt = true;
  spine.join();
  return during_steps;
}

TEST(SpineAllocations, BackendStep) { EXPECT_EQ(backend_step_allocations(false), 0); }

TEST(SpineAllocations, PacedBackendStepWithFreshObservations) {
  EXPECT_EQ(backend_step_allocations(true), 0);
}

}  // namespace
}  // namespace upkie_rl
