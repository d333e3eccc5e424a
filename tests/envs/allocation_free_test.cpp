/// Checks that environment steps allocate nothing (hot-path rule), on the Mock backend
/// (the Bullet engine's own allocations are the sim layer's business).

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>

#include "envs/registry.hpp"

namespace {
std::atomic<std::size_t> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* pointer = std::malloc(size == 0 ? 1 : size)) return pointer;
  throw std::bad_alloc();
}
void operator delete(void* pointer) noexcept { std::free(pointer); }
void operator delete(void* pointer, std::size_t) noexcept { std::free(pointer); }

namespace upkie_rl {
namespace {

TEST(AllocationFree, EnvironmentStepsAllocateNothing) {
  for (const char* id : {"Upkie-Mock-Servos", "Upkie-Mock-Pendulum", "Upkie-Mock-Gyropod",
                         "Upkie-Mock-ServosTask"}) {
    auto env = make_env(id);
    std::vector<float> observation(env->observation_space().size());
    std::vector<float> action(env->action_space().size());
    env->neutral_action(action);
    env->reset(0, observation);
    env->step(action, observation);  // warm-up
    const std::size_t before = g_allocations.load();
    for (int step = 0; step < 100; ++step) env->step(action, observation);
    EXPECT_EQ(g_allocations.load() - before, 0u) << id;
  }
}

TEST(AllocationFree, CounterCounts) {
  const std::size_t before = g_allocations.load();
  auto* leak_check = new std::vector<int>(10);
  delete leak_check;
  EXPECT_GE(g_allocations.load() - before, 2u);
}

}  // namespace
}  // namespace upkie_rl
