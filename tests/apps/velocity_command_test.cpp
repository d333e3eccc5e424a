/// The velocity task from the command line: the classical baseline tracks a command,
/// rollout reports tracking metrics and draws them, a short training improves the return
/// and logs each reward term.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "apps/cli_runner.hpp"
#include "rl/logging/scalar_csv_writer.hpp"

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

/// The summary of `rollout` of `controller` on MuJoCo for 250 steps (5 s) of the constant
/// command (vx, wz).
nlohmann::json constant_command_rollout(const std::string& controller, const std::string& vx,
                                        const std::string& wz, const std::string& extra = "") {
  const auto commands = temp_file("constant.csv");
  std::ofstream(commands) << "time,vx,wz\n0," << vx << "," << wz << "\n";
  const auto result =
      run_cli("rollout --env Upkie-MuJoCo-Velocity --controller " + controller +
              " --max-steps 250 --json --commands " + commands.string() + " " + extra);
  std::filesystem::remove(commands);
  EXPECT_EQ(result.exit_code, 0) << result.output;
  nlohmann::json summary = last_json(result.output);
  summary["output"] = result.output;
  return summary;
}

/// The "balancer:..." spec that `rollout` printed for `--controller lqr`.
std::string designed_spec(const std::string& output) {
  const std::size_t start = output.find("balancer:");
  return start == std::string::npos ? "" : output.substr(start, output.find('\n', start) - start);
}

/// The mean of `column` over rows [begin, begin + 3) of `table` (one iteration's mean
/// return is noisy).
double mean_of_three_rows(const ScalarTable& table, std::size_t begin, std::size_t column) {
  return (table.rows[begin][column] + table.rows[begin + 1][column] +
          table.rows[begin + 2][column]) /
         3.0;
}

/// The progress table of `upkie-rl train --config configs/<config> <overrides>` in a fresh
/// run directory named `name` (removed afterwards).
ScalarTable train_progress(const std::string& name, const std::string& config,
                           const std::string& overrides) {
  const auto run_dir = temp_file(name);
  std::filesystem::remove_all(run_dir);
  const auto result =
      run_cli("train --quiet --config " + std::string(UPKIE_RL_SOURCE_DIR) + "/configs/" + config +
              " --run-dir " + run_dir.string() + " " + overrides);
  EXPECT_EQ(result.exit_code, 0) << result.output;
  ScalarTable table = read_scalar_csv(run_dir / "progress.csv");
  std::filesystem::remove_all(run_dir);
  return table;
}

// The classical baseline (designed once by `--controller lqr`, then reused through its
// printed spec) holds a zero command and tracks a constant forward velocity and a constant
// yaw rate for 5 s without falling. The RMS errors count the response to the command's
// ramp from 0 at t = 0 (the task's command_max_acceleration, 1 m/s^2).
TEST(VelocityCommand, BaselineTracksConstantCommands) {
  const auto prefix = temp_file("plot");
  const nlohmann::json forward =
      constant_command_rollout("lqr", "0.5", "0", "--plot " + prefix.string());
  const std::string output = forward.at("output").get<std::string>();
  EXPECT_EQ(forward.at("fall_rate").get<double>(), 0.0) << output;
  EXPECT_LT(forward.at("tracking_rms_vx").get<double>(), 0.25) << output;
  EXPECT_LT(forward.at("tracking_rms_wz").get<double>(), 0.2) << output;
  EXPECT_TRUE(std::filesystem::exists(prefix.string() + "_forward_velocity.png"));
  EXPECT_TRUE(std::filesystem::exists(prefix.string() + "_yaw_rate.png"));
  const std::string spec = designed_spec(output);
  ASSERT_FALSE(spec.empty()) << output;

  const nlohmann::json still = constant_command_rollout(spec, "0", "0");
  EXPECT_EQ(still.at("fall_rate").get<double>(), 0.0) << still.at("output");
  EXPECT_LT(still.at("tracking_rms_vx").get<double>(), 0.08) << still.at("output");
  EXPECT_LT(still.at("tracking_rms_wz").get<double>(), 0.1) << still.at("output");

  const nlohmann::json turning = constant_command_rollout(spec, "0", "1.0");
  EXPECT_EQ(turning.at("fall_rate").get<double>(), 0.0) << turning.at("output");
  EXPECT_LT(turning.at("tracking_rms_wz").get<double>(), 0.5) << turning.at("output");
  EXPECT_LT(turning.at("tracking_rms_vx").get<double>(), 0.15) << turning.at("output");

  // Without the design's feedforward and filter (the pendulum's gains as a linear law, the
  // first baseline) the robot does not follow 0.5 m/s: the test can tell them apart.
  const nlohmann::json pendulum_law =
      constant_command_rollout("linear:9.11,0.404,0.289,0.0016", "0.5", "0");
  EXPECT_GT(pendulum_law.at("tracking_rms_vx").get<double>(), 0.4) << pendulum_law.at("output");
}

// The checked-in policy of the README (tests/data/policies/README.md) on the scripted
// commands: no fall, the README's figures (0.045 m/s, 0.123 rad/s; 0.121 m/s against the
// targets; the baseline alone: 0.063 m/s, 0.178 rad/s), and the metrics both ways.
TEST(VelocityCommand, CheckedInPolicyFollowsTheScriptedCommands) {
  const auto result = run_cli(
      "rollout --env Upkie-MuJoCo-Velocity --model " + std::string(UPKIE_RL_TEST_DATA_DIR) +
      "/policies/velocity_mujoco_seed0.ckpt --commands " + std::string(UPKIE_RL_SOURCE_DIR) +
      "/configs/velocity_commands.csv --max-steps 1000 --env-option max_episode_steps=1000 --json");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = last_json(result.output);
  EXPECT_EQ(summary.at("fall_rate").get<double>(), 0.0) << result.output;
  // Measured: 0.082 m/s on the robot's tires, with their rolling resistance (the policy
  // trained on the velocity task's former free-rolling tires followed at 0.05; on these it
  // does at 0.103).
  EXPECT_LT(summary.at("tracking_rms_vx").get<double>(), 0.1) << result.output;
  EXPECT_LT(summary.at("tracking_rms_wz").get<double>(), 0.15) << result.output;
  // The scripted rows are steps: the robot is further from them than from their ramps.
  EXPECT_GT(summary.at("tracking_rms_vx_target").get<double>(),
            summary.at("tracking_rms_vx").get<double>() + 0.02)
      << result.output;
  EXPECT_NEAR(summary.at("tracking_rms_wz_target").get<double>(),
              summary.at("tracking_rms_wz").get<double>(), 1e-9);  // yaw steps
}

/// Whether this C library's atan2f rounds as the one the returns below were recorded with
/// (glibc 2.36, Debian 12) at an input where that one is one ulp from the correctly rounded
/// value, which glibc 2.41's (Debian 13: CORE-MATH's) gives.
bool atan2f_rounds_as_recorded() {
  // volatile: atan2f of the C library at run time, not the compiler's folding (MPFR's,
  // correctly rounded).
  volatile float y = -0x1.e5c998p-4f;
  volatile float x = 0x1.ccd96p-1f;
  return std::atan2(static_cast<float>(y), static_cast<float>(x)) == -0x1.0c4eb8p-3f;
}

// A checkpoint of before the body-height command records no height_command nor
// leg_action_scale: it is read with their former defaults (false, 0.5), rebuilds the
// 20-component task it was trained on, and acts as it did: the returns of these three
// episodes, measured with the build of before the height command (main at 5db9ec1).
//
// The tolerance. Each return is a 500-step closed loop, which amplifies any rounding. The
// policy acts on top of the velocity balancer, which reads the pitch with atan2f (float), and
// C libraries round it differently: glibc 2.36's is one ulp off the correctly rounded value
// for about half the inputs, glibc 2.41's is correctly rounded. On Debian 13 the first reward
// differs by one float ulp at step 13, and the returns by 4.1e-4, 9.1e-6 and 1.6e-4 of
// themselves; with a correctly rounded atan2f preloaded on Debian 12, its returns are
// Debian 13's to the last bit (atan2f is the whole difference; libtorch is not used here).
// So the returns must be bit-identical (1e-9) where atan2f rounds as the recording's, and
// within 2e-3 elsewhere: 5 times the spread measured, and 5 to 12 times below what the
// regression this test guards does, the checkpoint read with today's leg_action_scale (1.0)
// instead of its former 0.5 (returns 0.98e-2, 2.4e-2 and 2.0e-2 higher).
TEST(VelocityCommand, CheckpointOfBeforeTheHeightCommandActsAsBefore) {
  const auto result =
      run_cli("rollout --env Upkie-MuJoCo-Velocity --model " + std::string(UPKIE_RL_TEST_DATA_DIR) +
              "/policies/velocity_mujoco_seed0.ckpt --episodes 3 --json");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = last_json(result.output);
  const std::vector<double> before = {2589.0620772488796, 2514.6033751864097, 2547.7981916660606};
  const auto returns = summary.at("returns").get<std::vector<double>>();
  ASSERT_EQ(returns.size(), before.size()) << result.output;
  const double relative_tolerance = atan2f_rounds_as_recorded() ? 1e-9 : 2e-3;
  for (std::size_t i = 0; i < before.size(); ++i) {
    EXPECT_NEAR(returns[i], before[i], relative_tolerance * before[i]) << "episode " << i;
  }
  EXPECT_TRUE(summary.at("tracking_rms_height").is_null()) << result.output;
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
  const auto result =
      run_cli("train --quiet --config " + config + " --run-dir " + run_dir.string() +
              " --set env.num_envs=8 --set env.mix_envs=2 --set env.threads=0 --set "
              "ppo.n_steps=2048 --set ppo.batch_size=512"
              " --set ppo.total_timesteps=81920 --set checkpoint_every=0"
              " --set env.options.max_episode_steps=200 --set env.options.residual_scale=0.3");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const ScalarTable table = read_scalar_csv(run_dir / "progress.csv");
  const std::size_t column = table.index("rollout/ep_rew_mean");
  const std::size_t tracking = table.index("episode/reward_track_forward_velocity");
  table.index("episode/reward_action_rate");
  ASSERT_GE(table.rows.size(), 6u);
  // Means of the first and last three iterations (one iteration's mean is noisy). The
  // config's residual_scale 0.1 leaves the baseline's near-maximal return little to gain in
  // 81,920 steps (956 then 952 measured); 0.3 starts the untrained residual further from it
  // (518 then 730 measured).
  const double first = mean_of_three_rows(table, 0, column);
  const double last = mean_of_three_rows(table, table.rows.size() - 3, column);
  EXPECT_GT(last, first + 8.0) << "first " << first << ", last " << last;
  EXPECT_TRUE(std::isfinite(table.rows.back()[tracking]));

  // The trained velocity policy drives: `drive --model` (no page: a zero command) applies
  // the task options it was trained with (its base controller) and keeps the robot up.
  std::filesystem::path model;
  for (const auto& entry : std::filesystem::directory_iterator(run_dir)) {
    if (entry.path().extension() == ".ckpt") model = entry.path();
  }
  ASSERT_FALSE(model.empty()) << "no final model in " << run_dir;
  const auto drive = run_cli("drive --env Upkie-MuJoCo-Velocity --model " + model.string() +
                             " --view-port 0 --view-speed 10 --duration 2");
  ASSERT_EQ(drive.exit_code, 0) << drive.output;
  EXPECT_NE(drive.output.find("drive: 100 steps (2 s simulated), 1 episode(s), 0 fall(s)"),
            std::string::npos)
      << drive.output;
  std::filesystem::remove_all(run_dir);
}

// configs/velocity_scratch.yaml, with no controller underneath, starts to stand within a
// few hundred thousand steps: the untrained policy falls within half a second (episodes of
// 25 steps, returns of 43 over the first three iterations); after 50 iterations (204,800
// steps) the episodes last 227 steps and the returns reach 505 (measured with the yaw ramp
// at 10 rad/s^2 and 5 epochs of 512 samples and their images; 235 and 554 with the ramp at
// 3 rad/s^2; 336 and 785 with 10 epochs of 1024; without mirror augmentation and the
// forward error's penalty 209-239 steps and 521-592; from straight legs, before: 16-19
// steps growing to 34-35).
TEST(VelocityCommand, ShortFromScratchTrainingLearnsToStand) {
  const ScalarTable table = train_progress("scratch", "velocity_scratch.yaml",
                                           "--set env.threads=0 --set ppo.total_timesteps=204800 "
                                           "--set checkpoint_every=0");
  ASSERT_GE(table.rows.size(), 50u);
  const std::size_t end = table.rows.size() - 3;
  // Lengths grow 9.1 times and returns 11.6 times (measured): both are asked for 4 times, so
  // that the test checks learning rather than this seed's exact pace.
  const std::pair<const char*, double> growths[] = {{"rollout/ep_len_mean", 4.0},
                                                    {"rollout/ep_rew_mean", 4.0}};
  for (const auto& [tag, growth] : growths) {
    const std::size_t column = table.index(tag);
    const double first = mean_of_three_rows(table, 0, column);
    const double last = mean_of_three_rows(table, end, column);
    EXPECT_GT(last, growth * first) << tag << ": first " << first << ", last " << last;
  }
}

// The same seed and thread count give the same from-scratch run: two runs of two
// iterations on the configuration's two environment threads log the same losses and
// returns to the last digit.
TEST(VelocityCommand, FromScratchRunRepeatsForTheSameSeed) {
  const std::string overrides = "--set ppo.total_timesteps=8192 --set checkpoint_every=0";
  const ScalarTable first = train_progress("scratch_a", "velocity_scratch.yaml", overrides);
  const ScalarTable second = train_progress("scratch_b", "velocity_scratch.yaml", overrides);
  ASSERT_EQ(first.rows.size(), 2u);
  ASSERT_EQ(second.rows.size(), 2u);
  for (const char* tag : {"train/loss", "train/approx_kl", "rollout/ep_rew_mean"}) {
    const std::size_t column = first.index(tag);
    for (std::size_t row = 0; row < 2; ++row) {
      EXPECT_EQ(first.rows[row][column], second.rows[row][column]) << tag << " " << row;
    }
  }
}

}  // namespace
}  // namespace upkie_rl
