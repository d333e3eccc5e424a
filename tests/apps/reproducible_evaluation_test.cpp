/// Reproducible evaluation: the same model, environment, options and seed give the same
/// `rollout` and `evaluate` figures on every run and for any thread count, with the random
/// parts on (observation noise, action lag, pushes, mass changes).

#include <gtest/gtest.h>

#include <string>

#include "apps/cli_runner.hpp"

namespace upkie_rl {
namespace {

using testing::run_cli;

const std::string kRobust =
    std::string(UPKIE_RL_TEST_DATA_DIR) + "/policies/pendulum_robust_mujoco_seed4.ckpt";

std::string last_line(std::string text) {
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return text.substr(text.rfind('\n') + 1);
}

TEST(ReproducibleEvaluation, RolloutFiguresRepeatForTheSameSeedAndChangeWithIt) {
  const std::string command =
      "rollout --env Upkie-MuJoCo-Pendulum --model " + kRobust +
      " --episodes 3 --json --env-option observation_noise=0.02 --env-option action_lag_max=0.02"
      " --seed ";
  const auto first = run_cli(command + "7");
  const auto second = run_cli(command + "7");
  const auto other = run_cli(command + "8");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_EQ(last_line(first.output), last_line(second.output));
  EXPECT_EQ(last_line(first.output).front(), '{');
  // The seed matters: another one draws other noise (so the equality above is not trivial).
  EXPECT_NE(last_line(first.output), last_line(other.output));
}

TEST(ReproducibleEvaluation, EvaluateFiguresRepeatForAnyThreadCount) {
  const std::string command = "evaluate --env Upkie-MuJoCo-Pendulum --model robust=" + kRobust +
                              " --grid push=0:30:15,mass=0.8:1.2:0.4 --episodes 3 --seed 5 --json"
                              " --env-option observation_noise=0.02 --threads ";
  const auto one = run_cli(command + "1");
  const auto two = run_cli(command + "2");
  const auto again = run_cli(command + "2");
  ASSERT_EQ(one.exit_code, 0) << one.output;
  EXPECT_EQ(last_line(one.output), last_line(two.output));
  EXPECT_EQ(last_line(two.output), last_line(again.output));
}

}  // namespace
}  // namespace upkie_rl
