#include "rl/logging/reward_term_statistics.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace upkie_rl {
namespace {

TEST(RewardTermStatistics, MeanOverTheLastEpisodes) {
  RewardTermStatistics statistics(2, 3);
  EXPECT_TRUE(std::isnan(statistics.mean(0)));
  for (double episode : {1.0, 2.0, 3.0, 4.0}) {
    const std::array<double, 2> terms{episode, -10.0 * episode};
    statistics.add(terms);
  }
  EXPECT_EQ(statistics.size(), 3u);
  EXPECT_DOUBLE_EQ(statistics.mean(0), 3.0);  // episodes 2, 3, 4
  EXPECT_DOUBLE_EQ(statistics.mean(1), -30.0);
  EXPECT_TRUE(std::isnan(statistics.mean(2)));
}

}  // namespace
}  // namespace upkie_rl
