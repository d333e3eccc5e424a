/// Checks that vector steps (synchronous, thread pool, normalised) allocate nothing.

#include <gtest/gtest.h>

#include "common/allocation_counter.hpp"

#include <vector>

#include "vec/make_vector_env.hpp"
#include "vec/vec_normalize.hpp"

namespace upkie_rl {
namespace {

std::size_t allocations_over_steps(VectorEnv& venv, int steps) {
  std::vector<float> actions(venv.num_envs() * venv.action_space().size(), 0.0f);
  venv.reset(0);
  venv.step(actions);  // warm-up
  const std::size_t before = testing::all_threads_allocations.load();
  for (int step = 0; step < steps; ++step) venv.step(actions);
  return testing::all_threads_allocations.load() - before;
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
  // The velocity task sums its reward terms per episode as well.
  VecNormalize velocity(
      make_vector_env("Upkie-Mock-Velocity", {{"max_episode_steps", "100"}}, 2, 0), {});
  EXPECT_EQ(allocations_over_steps(velocity, 350), 0u);
}

}  // namespace
}  // namespace upkie_rl
