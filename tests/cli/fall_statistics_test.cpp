#include "cli/fall_statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace upkie_rl::apps {
namespace {

// Clopper-Pearson's one-sided bound has a closed form without falls: 1 - alpha^(1/n).
TEST(FallStatistics, UpperBoundWithoutFallsIsTheClosedForm) {
  for (const int episodes : {1, 20, 100}) {
    EXPECT_NEAR(fall_rate_upper_bound(0, episodes), 1.0 - std::pow(0.05, 1.0 / episodes), 1e-9)
        << episodes;
  }
  EXPECT_NEAR(fall_rate_upper_bound(0, 20, 0.99), 1.0 - std::pow(0.01, 1.0 / 20), 1e-9);
}

// At the bound, the observed count or fewer happens with probability alpha.
TEST(FallStatistics, AtTheUpperBoundTheCountOrFewerHasProbabilityAlpha) {
  for (const int falls : {1, 3, 10}) {
    const double rate = fall_rate_upper_bound(falls, 20);
    double at_most = 0.0;
    for (int k = 0; k <= falls; ++k) {
      at_most += std::tgamma(21.0) / (std::tgamma(k + 1.0) * std::tgamma(21.0 - k)) *
                 std::pow(rate, k) * std::pow(1.0 - rate, 20 - k);
    }
    EXPECT_NEAR(at_most, 0.05, 1e-6) << falls;
    EXPECT_GT(rate, falls / 20.0) << falls;
  }
  EXPECT_EQ(fall_rate_upper_bound(20, 20), 1.0);
  EXPECT_TRUE(std::isnan(fall_rate_upper_bound(0, 0)));
  EXPECT_TRUE(std::isnan(fall_rate_upper_bound(3, 2)));
}

TEST(FallStatistics, FisherTestOfMoreFalls) {
  // One fall against none: a's share of the one fall is a's share of the episodes.
  EXPECT_NEAR(more_falls_p_value(1, 20, 0, 20), 0.5, 1e-12);
  EXPECT_NEAR(more_falls_p_value(1, 20, 0, 60), 0.25, 1e-12);
  // 2 against 0 of 20: both falls in a's 20 of 40 episodes, C(20,2) / C(40,2).
  EXPECT_NEAR(more_falls_p_value(2, 20, 0, 20), 190.0 / 780.0, 1e-12);
  EXPECT_LT(more_falls_p_value(15, 20, 1, 20), 1e-5);
  EXPECT_GT(more_falls_p_value(1, 20, 15, 20), 0.999);
  EXPECT_EQ(more_falls_p_value(0, 20, 5, 20), 1.0);
  // Where a must take falls (b has too few episodes for them all): the bottom of the support.
  EXPECT_EQ(more_falls_p_value(20, 20, 20, 20), 1.0);
  EXPECT_EQ(more_falls_p_value(2, 4, 4, 4), 1.0);
  // 4 and 2 of 4: a takes all 4 of its episodes' falls, C(4,4) C(4,2) / C(8,6).
  EXPECT_NEAR(more_falls_p_value(4, 4, 2, 4), 6.0 / 28.0, 1e-12);
  // 3 and 3 of 4: a takes 2, 3 or 4 of the 6 falls, C(4,k) C(4,6-k) / 28 = 6, 16, 6 / 28.
  EXPECT_NEAR(more_falls_p_value(3, 4, 3, 4), 22.0 / 28.0, 1e-12);
  EXPECT_TRUE(std::isnan(more_falls_p_value(1, 0, 0, 20)));
  EXPECT_TRUE(std::isnan(more_falls_p_value(1, 20, 21, 20)));
}

}  // namespace
}  // namespace upkie_rl::apps
