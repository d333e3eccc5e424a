/// The velocity task from the command line: the classical baseline tracks a command,
/// rollout reports tracking metrics and draws them, a short training improves the return
/// and logs each reward term.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "apps/cli_runner.hpp"
#include "rl/scalar_csv_writer.hpp"

namespace upkie_rl {
namespace {

using testing::run_cli;

std::filesystem::path temp_file(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("upkie_rl_velocity_" + std::to_string(::getpid()) + "_" + name);
}

/// The JSON summary on the last line of `output`.
nlohmann::json last_json(const std::string& output) {
  const std::size_t start = output.rfind("\n{");
  return nlohmann::json::parse(output.substr(start == std::string::npos ? 0 : start + 1));
}

// The baseline holds a zero command; it does not yet follow a moving one (it falls within
// 2 s at 0.5 m/s: docs/environments.md, "The classical baseline").
TEST(VelocityCommand, BaselineHoldsAZeroCommand) {
  const auto commands = temp_file("constant.csv");
  std::ofstream(commands) << "time,vx,wz\n0,0,0\n";
  const auto prefix = temp_file("plot");
  const auto result = run_cli(
      "rollout --env Upkie-MuJoCo-Velocity --controller lqr --max-steps 500 --json "
      "--commands " +
      commands.string() + " --plot " + prefix.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = last_json(result.output);
  EXPECT_EQ(summary.at("fall_rate").get<double>(), 0.0) << result.output;
  EXPECT_LT(summary.at("tracking_rms_vx").get<double>(), 0.05) << result.output;
  EXPECT_LT(summary.at("tracking_rms_wz").get<double>(), 0.05) << result.output;
  EXPECT_TRUE(std::filesystem::exists(prefix.string() + "_forward_velocity.png"));
  EXPECT_TRUE(std::filesystem::exists(prefix.string() + "_yaw_rate.png"));
  std::filesystem::remove(commands);
}

TEST(VelocityCommand, ZeroControllerFallsAndMetricsSaySo) {
  const auto result = run_cli(
      "rollout --env Upkie-MuJoCo-Velocity --controller zero --episodes 2 --json "
      "--env-option init_rand_pitch=0.2");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = last_json(result.output);
  EXPECT_EQ(summary.at("fall_rate").get<double>(), 1.0) << result.output;
  EXPECT_TRUE(summary.contains("tracking_rms_vx"));
  // Other tasks have no tracking figures, and refuse --commands.
  const auto pendulum = run_cli("rollout --env Upkie-Mock-Pendulum --max-steps 5 --json");
  EXPECT_FALSE(last_json(pendulum.output).contains("tracking_rms_vx")) << pendulum.output;
  const auto refused = run_cli("rollout --env Upkie-Mock-Pendulum --plot x");
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.output.find("velocity task"), std::string::npos) << refused.output;
}

TEST(VelocityCommand, ShortTrainingImprovesTheReturnAndLogsEachTerm) {
  const auto run_dir = temp_file("train");
  std::filesystem::remove_all(run_dir);
  const std::string config = std::string(UPKIE_RL_SOURCE_DIR) + "/configs/velocity.yaml";
  const auto result = run_cli(
      "train --quiet --config " + config + " --run-dir " + run_dir.string() +
      " --set env.num_envs=8 --set env.threads=0 --set ppo.n_steps=2048 --set ppo.batch_size=512"
      " --set ppo.total_timesteps=81920 --set checkpoint_every=0"
      " --set env.options.max_episode_steps=200");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const ScalarTable table = read_scalar_csv(run_dir / "progress.csv");
  const std::size_t column = table.index("rollout/ep_rew_mean");
  const std::size_t tracking = table.index("episode/reward_track_forward_velocity");
  table.index("episode/reward_action_rate");
  ASSERT_GE(table.rows.size(), 6u);
  // Means of the first and last three iterations (one iteration's mean is noisy); measured:
  // about 43 then 59 (episodes of at most 200 steps, up to 5.5 per step).
  const auto mean_of = [&](std::size_t begin) {
    return (table.rows[begin][column] + table.rows[begin + 1][column] +
            table.rows[begin + 2][column]) /
           3.0;
  };
  const double first = mean_of(0);
  const double last = mean_of(table.rows.size() - 3);
  EXPECT_GT(last, first + 8.0) << "first " << first << ", last " << last;
  EXPECT_TRUE(std::isfinite(table.rows.back()[tracking]));
  std::filesystem::remove_all(run_dir);
}

}  // namespace
}  // namespace upkie_rl
