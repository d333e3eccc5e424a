#include "envs/tasks/balance_termination.hpp"

#include <gtest/gtest.h>

namespace upkie_rl {
namespace {

using Reason = BalanceTermination::Reason;

TEST(BalanceTermination, SeedThresholds) {
  const BalanceTermination termination;
  EXPECT_EQ(termination.check(0.99, 4.9, 9.9, 1.9), Reason::kNone);
  EXPECT_EQ(termination.check(-1.01, 0.0, 0.0, 0.0), Reason::kFall);
  EXPECT_EQ(termination.check(0.0, -5.01, 0.0, 0.0), Reason::kPositionDrift);
  EXPECT_EQ(termination.check(0.0, 0.0, 10.01, 0.0), Reason::kAngularVelocity);
  EXPECT_EQ(termination.check(0.0, 0.0, 0.0, -2.01), Reason::kLinearVelocity);
  // Strict inequalities: the threshold itself does not terminate.
  EXPECT_EQ(termination.check(1.0, 5.0, 10.0, 2.0), Reason::kNone);
}

TEST(BalanceTermination, CheckedInTheSeedOrder) {
  const BalanceTermination termination;
  EXPECT_EQ(termination.check(2.0, 6.0, 11.0, 3.0), Reason::kFall);
  EXPECT_EQ(termination.check(0.0, 6.0, 11.0, 3.0), Reason::kPositionDrift);
  EXPECT_EQ(termination.check(0.0, 0.0, 11.0, 3.0), Reason::kAngularVelocity);
  EXPECT_EQ(termination.check(0.0, 0.0, 0.0, 3.0), Reason::kLinearVelocity);
  EXPECT_STREQ(to_string(Reason::kPositionDrift), "position_drift");
}

}  // namespace
}  // namespace upkie_rl
