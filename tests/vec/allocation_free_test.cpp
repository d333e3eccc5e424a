/// Checks that vector steps (synchronous, thread pool, normalised) allocate nothing.

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>

#include "vec/make_vector_env.hpp"
#include "vec/vec_normalize.hpp"

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

std::size_t allocations_over_steps(VectorEnv& venv, int steps) {
  std::vector<float> actions(venv.num_envs() * venv.action_space().size(), 0.0f);
  venv.reset(0);
  venv.step(actions);  // warm-up
  const std::size_t before = g_allocations.load();
  for (int step = 0; step < steps; ++step) venv.step(actions);
  return g_allocations.load() - before;
}

TEST(AllocationFree, VectorStepsAllocateNothing) {
  // 350 steps: episodes of 300 steps end, so auto-resets are on the path too.
  const EnvOptions options;
  auto sync = make_vector_env("Upkie-Mock-Pendulum", options, 3, 0);
  EXPECT_EQ(allocations_over_steps(*sync, 350), 0u);
  auto pooled = make_vector_env("Upkie-Mock-Pendulum", options, 3, 2);
  EXPECT_EQ(allocations_over_steps(*pooled, 350), 0u);
  VecNormalize normalized(make_vector_env("Upkie-Mock-ServosTask", options, 2, 0), {});
  EXPECT_EQ(allocations_over_steps(normalized, 350), 0u);
}

}  // namespace
}  // namespace upkie_rl
