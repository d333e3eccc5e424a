#include "rl/ppo/linear_schedule.hpp"

#include <gtest/gtest.h>

namespace upkie_rl {
namespace {

TEST(LinearSchedule, GoesFromInitialToFinal) {
  const LinearSchedule schedule{2e-4, 1e-5};
  EXPECT_DOUBLE_EQ(schedule(1.0), 2e-4);
  EXPECT_DOUBLE_EQ(schedule(0.0), 1e-5);
  EXPECT_DOUBLE_EQ(schedule(0.5), 1e-5 + 0.5 * (2e-4 - 1e-5));
  EXPECT_DOUBLE_EQ(schedule(-0.1), 1e-5);  // past the end (the last rollout overshoots)
}

TEST(LinearSchedule, ProgressRemainingIsOneMinusTheFractionDone) {
  EXPECT_DOUBLE_EQ(LinearSchedule::progress_remaining(0, 1000), 1.0);
  EXPECT_DOUBLE_EQ(LinearSchedule::progress_remaining(2040, 1'000'000), 1.0 - 0.00204);
  EXPECT_DOUBLE_EQ(LinearSchedule::progress_remaining(1000, 1000), 0.0);
}

}  // namespace
}  // namespace upkie_rl
