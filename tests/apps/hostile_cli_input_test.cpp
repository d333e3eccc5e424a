// Fault injection (issue 26) through the real command line, second audit: a fresh training
// never writes among a user's files, a refused start leaves no run directory behind.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "apps/clean_refusal.hpp"
#include "apps/cli_runner.hpp"
#include "common/temp_files.hpp"

namespace upkie_rl {
namespace {

using testing::expect_clean_refusal;
using testing::run_cli;

const std::string kTrain =
    "train --quiet --config " + std::string(UPKIE_RL_SOURCE_DIR) +
    "/configs/pendulum.yaml --set env.id=Upkie-Mock-Pendulum --set env.num_envs=2"
    " --set env.threads=0 --set ppo.n_steps=64 --set ppo.batch_size=32 --set ppo.n_epochs=1"
    " --set ppo.total_timesteps=128 --set policy.actor_hidden_sizes=[8]"
    " --set policy.critic_hidden_sizes=[8]";

std::filesystem::path fresh_directory(const std::string& name) {
  const auto path = testing::temp_path(name, "upkie_rl_hostile_cli");
  std::filesystem::remove_all(path);
  return path;
}

std::size_t entries(const std::filesystem::path& directory) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(directory),
                                                std::filesystem::directory_iterator()));
}

TEST(HostileCliInput, FreshTrainingAmongAUsersFilesIsRefusedAndTouchesNothing) {
  for (const std::string name : {"config.yaml", "progress.csv", "notes.txt"}) {
    const auto user_dir = fresh_directory("user_" + name);
    std::filesystem::create_directories(user_dir);
    const std::string bytes = "the user's own " + name + "\n";
    testing::write_bytes(user_dir / name, bytes);
    expect_clean_refusal(kTrain + " --run-dir " + user_dir.string(), "not an upkie-rl run");
    EXPECT_EQ(testing::read_bytes(user_dir / name), bytes) << name;
    EXPECT_EQ(entries(user_dir), 1u) << name;  // no .lock, no config.yaml
  }
  // Asked for explicitly, it trains there.
  const auto forced = fresh_directory("user_forced");
  std::filesystem::create_directories(forced);
  testing::write_bytes(forced / "config.yaml", "mine: 1\n");
  const testing::CliResult result =
      run_cli(kTrain + " --force-run-dir --run-dir " + forced.string());
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(testing::read_bytes(forced / "config.yaml"), "mine: 1\n");
}

TEST(HostileCliInput, RefusedStartsLeaveNoRunDirectoryBehind) {
  const auto parent = fresh_directory("refused_parent");
  const auto run_dir = parent / "run";
  for (const auto& [flags, culprit] : std::vector<std::pair<std::string, std::string>>{
           {"--set env.options.frequency=nan", "frequency"},
           {"--set env.options.max_episode_steps=-1", "max_episode_steps"},
           {"--set env.options.bogus=1", "bogus"},
           {"--view --view-port 0 --view-env 5", "environment 5"},
           {"--view --view-port 0 --view-host 999.1.1.1", "999.1.1.1"}}) {
    expect_clean_refusal(kTrain + " " + flags + " --run-dir " + run_dir.string(), culprit);
    EXPECT_FALSE(std::filesystem::exists(parent)) << flags;  // nor the parent it created
  }
  // An empty directory of the user's stays, empty.
  std::filesystem::create_directories(run_dir);
  expect_clean_refusal(kTrain + " --view --view-port 0 --view-env 5 --run-dir " + run_dir.string(),
                       "environment 5");
  EXPECT_TRUE(std::filesystem::is_directory(run_dir));
  EXPECT_EQ(entries(run_dir), 0u);
}

TEST(HostileCliInput, EmptyOutputPathsAreRefused) {
  expect_clean_refusal("view --html '' " + std::string(UPKIE_RL_SOURCE_DIR) + "/CMakeLists.txt",
                       "--html");
  expect_clean_refusal("rollout --env Upkie-Mock-Velocity --max-steps 5 --plot ''", "--plot");
  expect_clean_refusal("evaluate --env Upkie-Mock-Pendulum --controller zero --output ''",
                       "--output");
  expect_clean_refusal("sweep --plan --config " + std::string(UPKIE_RL_SOURCE_DIR) +
                           "/configs/pendulum.yaml --seeds 0:1 --output ''",
                       "--output");
  expect_clean_refusal(
      "train --config " + std::string(UPKIE_RL_SOURCE_DIR) + "/configs/pendulum.yaml --run-dir ''",
      "--run-dir");
}

TEST(HostileCliInput, SeedsOutsideTheirRangeAreRefusedNotWrapped) {
  for (const std::string seed : {"-1", "18446744073709551616", "1e3", "nan"}) {
    expect_clean_refusal("rollout --env Upkie-Mock-Pendulum --max-steps 5 --seed " + seed,
                         "--seed: " + seed);
    expect_clean_refusal("evaluate --env Upkie-Mock-Pendulum --controller zero --seed " + seed,
                         "--seed: " + seed);
    expect_clean_refusal(kTrain + " --seed " + seed, "--seed: " + seed);
    expect_clean_refusal("drive --env Upkie-Mock-Velocity --seed " + seed, "--seed: " + seed);
    expect_clean_refusal(
        "identify --log " + std::string(UPKIE_RL_SOURCE_DIR) + "/CMakeLists.txt --seed " + seed,
        "--seed: " + seed);
  }
  EXPECT_EQ(run_cli("rollout --env Upkie-Mock-Pendulum --max-steps 5 --seed 18446744073709551615")
                .exit_code,
            0);
}

TEST(HostileCliInput, NumericFlagsRefuseNanAndNameTheirRangeShortly) {
  for (const auto& [arguments, culprit] : std::vector<std::pair<std::string, std::string>>{
           {kTrain + " --view-env -1", "--view-env: -1 is not a finite number in [0, 4095]"},
           {kTrain + " --view-env nan", "--view-env: nan"},
           {"sweep /nonexistent --run -1", "--run: -1 is not a finite number in [0, 9999]"},
           {"bench --env Upkie-Mock-Pendulum --num-envs nan", "--num-envs: nan"},
           {"plot /nonexistent --window inf", "--window: inf"},
           {"rollout --env Upkie-Mock-Pendulum --view --view-wait nan", "--view-wait: nan"},
           {"rollout --env Upkie-Mock-Pendulum --max-steps 5 --video x.gif --video-size 640x480x3",
            "--video-size"}}) {
    expect_clean_refusal(arguments, culprit);
    // No 300-digit DBL_MAX in the message.
    EXPECT_EQ(run_cli(arguments).output.find("17976931348623157"), std::string::npos) << arguments;
  }
}

TEST(HostileCliInput, PlotOfAShortRunNamesTheFiguresItCannotDrawAndKeepsTheFormerOnes) {
  const auto run_dir = fresh_directory("short_run");
  std::filesystem::create_directories(run_dir);
  // Two updates, no episode ended: no return nor length to draw.
  testing::write_bytes(run_dir / "progress.csv",
                       "time/total_timesteps,rollout/ep_rew_mean,rollout/ep_len_mean,train/loss,"
                       "train/approx_kl\n64,,,4.5,0.001\n128,,,0.5,0.002\n");
  testing::write_bytes(run_dir / "return.png", "former figure");
  expect_clean_refusal("plot " + run_dir.string(), "return.png, length.png not drawn");
  EXPECT_EQ(testing::read_bytes(run_dir / "return.png"), "former figure");
  EXPECT_FALSE(std::filesystem::exists(run_dir / "length.png"));
  EXPECT_GT(std::filesystem::file_size(run_dir / "loss.png"), 0u);
  for (const auto& entry : std::filesystem::directory_iterator(run_dir)) {
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path();
  }
}

}  // namespace
}  // namespace upkie_rl
