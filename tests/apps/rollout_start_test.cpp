/// Every printed evaluation says which start its episodes had (issue #36: a figure from the
/// exact start was read as one from random starts).

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "apps/cli_runner.hpp"

namespace upkie_rl {
namespace {

using testing::run_cli;

TEST(RolloutStart, SummaryLineSaysRandomStartsByDefault) {
  const auto result = run_cli(
      "rollout --env Upkie-MuJoCo-Pendulum --controller linear:10,1,0,0.1 --episodes 2 "
      "--max-steps 20 --json");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("over 2 episodes from random starts, mean length"),
            std::string::npos)
      << result.output;
  EXPECT_EQ(nlohmann::json::parse(result.lines().back())["start"], "from random starts");
}

TEST(RolloutStart, SummaryLineSaysTheExactStart) {
  const auto result = run_cli(
      "rollout --env Upkie-MuJoCo-Pendulum --controller linear:10,1,0,0.1 --episodes 1 "
      "--max-steps 20 --exact-start --json");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("over 1 episodes from the exact start (--exact-start), mean"),
            std::string::npos)
      << result.output;
  EXPECT_EQ(result.output.find("random"), std::string::npos) << result.output;
}

TEST(EvaluateStart, TableSaysTheExactStart) {
  const auto result = run_cli(
      "evaluate --env Upkie-MuJoCo-Pendulum --controller zero --episodes 1 --max-steps 20 "
      "--exact-start");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("zero (success rate over 1 episodes per cell from the exact start"),
            std::string::npos)
      << result.output;
}

}  // namespace
}  // namespace upkie_rl
