#include "envs/tasks/balance_reward.hpp"

#include <gtest/gtest.h>

namespace upkie_rl {
namespace {

TEST(BalanceReward, MaximumIsOneInTheIdealState) {
  BalanceReward reward;
  EXPECT_DOUBLE_EQ(reward(0.0, 0.0, 0.0, 0.0), 1.0);
}

TEST(BalanceReward, PendulumWeightsOnHandComputedSteps) {
  BalanceReward reward(BalanceRewardWeights::pendulum());
  // Step 1: Δa = 0.5 and Δ²a = 0.5 (history zero at reset).
  // 1 - (2·0.01 + 0.5·0.04 + 0.5·0.09 + 1·0.25 + 2·0.25 + 1.5·0.25) = -0.21
  EXPECT_NEAR(reward(0.1, 0.2, 0.3, 0.5), -0.21, 1e-12);
  // Step 2: a = 0.3, Δa = -0.2, Δ²a = -0.7: 1 - (0.09 + 2·0.04 + 1.5·0.49) = 0.095
  EXPECT_NEAR(reward(0.0, 0.0, 0.0, 0.3), 0.095, 1e-12);
  // Step 3: a = 0.3, Δa = 0, Δ²a = 0.2: 1 - (0.09 + 1.5·0.04) = 0.85
  EXPECT_NEAR(reward(0.0, 0.0, 0.0, 0.3), 0.85, 1e-12);
  reward.reset();
  // After reset the history is zero again: same as step 1.
  EXPECT_NEAR(reward(0.1, 0.2, 0.3, 0.5), -0.21, 1e-12);
}

TEST(BalanceReward, ServosWeights) {
  BalanceReward reward(BalanceRewardWeights::servos());
  // 1 - (0.5·0.04 + 0.1·1 + 0.1·0.25 + 0.05·4 + 0.01·4 + 0.005·4) = 0.595
  EXPECT_NEAR(reward(0.2, 1.0, -0.5, 2.0), 0.595, 1e-12);
}

}  // namespace
}  // namespace upkie_rl
