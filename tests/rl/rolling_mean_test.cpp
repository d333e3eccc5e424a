#include "rl/logging/rolling_mean.hpp"

#include <gtest/gtest.h>

namespace upkie_rl {
namespace {

TEST(RollingMean, TrailingWindowWithPartialStartAndNaNSkipped) {
  const double nan = std::nan("");
  const std::vector<double> values{1, 2, 3, nan, 5, 6};
  const std::vector<double> mean = rolling_mean(values, 3);
  EXPECT_DOUBLE_EQ(mean[0], 1.0);
  EXPECT_DOUBLE_EQ(mean[1], 1.5);
  EXPECT_DOUBLE_EQ(mean[2], 2.0);
  EXPECT_DOUBLE_EQ(mean[3], 2.5);  // (2 + 3) / 2
  EXPECT_DOUBLE_EQ(mean[4], 4.0);  // (3 + 5) / 2
  EXPECT_DOUBLE_EQ(mean[5], 5.5);  // (5 + 6) / 2
  EXPECT_TRUE(std::isnan(rolling_mean({nan, nan}, 2)[1]));
}

}  // namespace
}  // namespace upkie_rl
