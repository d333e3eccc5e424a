#include "rl/ppo/rollout_buffer.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace upkie_rl {
namespace {

TEST(ComputeGae, MatchesHandComputedValuesAcrossAnEpisodeEnd) {
  // Two envs, three steps, step-major: index t * 2 + env. γ = 0.9, λ = 0.5.
  // Env 0: r = (1, 2, 3), V = (0.5, 1, 1.5), its episode ends at t = 1, V_last = 2.
  // Env 1: r = (1, 1, 1), V = 0, no episode end, V_last = 1.
  const std::vector<float> rewards{1, 1, 2, 1, 3, 1};
  const std::vector<float> values{0.5f, 0, 1.0f, 0, 1.5f, 0};
  const std::vector<float> dones{0, 0, 1, 0, 0, 0};
  const std::vector<float> last_values{2.0f, 1.0f};
  std::vector<float> advantages(6), returns(6);
  compute_gae(rewards, values, dones, last_values, 3, 2, 0.9, 0.5, advantages, returns);
  // Env 0, by hand:
  //   t=2: δ = 3 + 0.9·2 − 1.5 = 3.3, A = 3.3
  //   t=1: done, δ = 2 − 1 = 1, A = 1 (nothing flows back across the episode end)
  //   t=0: δ = 1 + 0.9·1 − 0.5 = 1.4, A = 1.4 + 0.45·1 = 1.85
  EXPECT_NEAR(advantages[4], 3.3, 1e-6);
  EXPECT_NEAR(advantages[2], 1.0, 1e-6);
  EXPECT_NEAR(advantages[0], 1.85, 1e-6);
  EXPECT_NEAR(returns[4], 4.8, 1e-6);
  EXPECT_NEAR(returns[2], 2.0, 1e-6);
  EXPECT_NEAR(returns[0], 2.35, 1e-6);
  // Env 1: t=2: δ = 1 + 0.9·1 = 1.9; t=1: 1 + 0.45·1.9 = 1.855; t=0: 1 + 0.45·1.855.
  EXPECT_NEAR(advantages[5], 1.9, 1e-6);
  EXPECT_NEAR(advantages[3], 1.855, 1e-6);
  EXPECT_NEAR(advantages[1], 1.83475, 1e-6);
  EXPECT_NEAR(returns[1], 1.83475, 1e-6);
}

TEST(ComputeGae, LambdaOneGivesDiscountedReturnsAndLambdaZeroTdErrors) {
  const std::vector<float> rewards{1, 1, 1};
  const std::vector<float> values{0.2f, 0.4f, 0.6f};
  const std::vector<float> dones{0, 0, 0};
  const std::vector<float> last_values{10.0f};
  std::vector<float> advantages(3), returns(3);
  compute_gae(rewards, values, dones, last_values, 3, 1, 0.5, 1.0, advantages, returns);
  // λ = 1: returns are the discounted returns bootstrapped with V_last.
  EXPECT_NEAR(returns[2], 1 + 0.5 * 10, 1e-6);
  EXPECT_NEAR(returns[1], 1 + 0.5 * 6, 1e-6);
  EXPECT_NEAR(returns[0], 1 + 0.5 * 4, 1e-6);
  compute_gae(rewards, values, dones, last_values, 3, 1, 0.5, 0.0, advantages, returns);
  // λ = 0: one-step TD errors.
  EXPECT_NEAR(advantages[0], 1 + 0.5 * 0.4 - 0.2, 1e-6);
  EXPECT_NEAR(advantages[1], 1 + 0.5 * 0.6 - 0.4, 1e-6);
  EXPECT_NEAR(advantages[2], 1 + 0.5 * 10 - 0.6, 1e-6);
}

TEST(ComputeGae, RejectsMismatchedSizes) {
  std::vector<float> three(3), two(2), one(1);
  EXPECT_THROW(compute_gae(three, three, two, one, 3, 1, 0.9, 0.9, three, three),
               std::invalid_argument);
  EXPECT_THROW(compute_gae(three, three, three, two, 3, 1, 0.9, 0.9, three, three),
               std::invalid_argument);
}

TEST(RolloutBuffer, RowsAreStepMajorAndFlatViewsSeeThem) {
  RolloutBuffer buffer(2, 3, 4, 1);
  EXPECT_EQ(buffer.size(), 6);
  buffer.observations(1)[2 * 4 + 3] = 7.0f;  // step 1, env 2, component 3
  buffer.values(1)[2] = 5.0f;
  EXPECT_FLOAT_EQ(buffer.flat_observations()[5][3].item<float>(), 7.0f);
  EXPECT_FLOAT_EQ(buffer.flat_values()[5].item<float>(), 5.0f);
  const std::vector<float> last{0, 0, 0};
  buffer.rewards(1)[2] = 1.0f;
  buffer.compute_returns_and_advantages(last, 0.9, 0.95);
  EXPECT_FLOAT_EQ(buffer.flat_advantages()[5].item<float>(), 1.0f - 5.0f);
  EXPECT_FLOAT_EQ(buffer.flat_returns()[5].item<float>(), 1.0f);
}

}  // namespace
}  // namespace upkie_rl
