// The spine link's per-step paths allocate nothing once warmed up: the agent's step
// (pack the action, wait, decode the observation) and the server's Action cycle (decode,
// merge into the action dictionary, step, write the observation).

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <thread>

#include "fake_simulation.hpp"
#include "spine/reset_config.hpp"
#include "spine/servo_action_message.hpp"
#include "spine/spine_backend.hpp"
#include "spine/spine_server.hpp"

namespace {

/// Allocations made by the current thread while counting is on.
thread_local bool counting = false;
thread_local long allocations = 0;

}  // namespace

// Counting replacements of the global allocation functions (for this test program).
void* operator new(std::size_t size) {
  if (counting) ++allocations;
  if (void* pointer = std::malloc(size == 0 ? 1 : size)) return pointer;
  throw std::bad_alloc();
}
void operator delete(void* pointer) noexcept { std::free(pointer); }
void operator delete(void* pointer, std::size_t) noexcept { std::free(pointer); }

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
  simulation.actions.reserve(100);  // the fake's own record must not count

  long during_steps = 0;
  for (int step = 0; step < 50; ++step) {
    write_servo_action_msgpack(moving_action(step), message);
    agent.write_payload({message.data(), message.size()});
    agent.set_request(Request::kAction);
    counting = step >= 5;  // warm-up: buffers grow to their working size
    allocations = 0;
    server.cycle();
    counting = false;
    during_steps += allocations;
    ASSERT_EQ(agent.request(), 0u);
  }
  EXPECT_EQ(during_steps, 0);
  EXPECT_DOUBLE_EQ(simulation.actions.back()[kLeftWheel].velocity, 0.49);
}

TEST(SpineAllocations, BackendStep) {
  testing::FakeSimulation simulation;
  SpineServerConfig server_config;
  server_config.shm_name = testing::unique_shm_name("alloc_backend");
  server_config.real_time = false;
  SpineServer server(simulation, server_config);
  simulation.actions.reserve(100);
  std::atomic<bool> interrupt{false};
  std::thread spine([&] { server.run(interrupt); });

  SpineBackendConfig config;
  config.shm_name = server_config.shm_name;
  config.regulate_frequency = false;
  config.open_tries = 1;
  long during_steps = 0;
  {
    SpineBackend backend(config);
    backend.reset(ResetState{});
    for (int step = 0; step < 50; ++step) {
      const ServoAction action = moving_action(step);
      counting = step >= 5;
      allocations = 0;
      backend.step(action);
      counting = false;
      during_steps += allocations;
    }
    EXPECT_NEAR(backend.observation().time, 50 * 0.005, 1e-12);
  }
  interrupt = true;
  spine.join();
  EXPECT_EQ(during_steps, 0);
}

}  // namespace
}  // namespace upkie_rl
