/// `upkie-rl train` as ranks of a data-parallel run (DD-PPO), from the real binary: the
/// launcher's variables set by the test, and torchrun itself when it is installed.

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "apps/cli_runner.hpp"
#include "common/background_process.hpp"
#include "common/shell_output.hpp"
#include "common/temp_files.hpp"

namespace upkie_rl {
namespace {

using testing::free_port;
using testing::read_bytes;
using testing::temp_path;
using Process = testing::BackgroundProcess;

/// `upkie-rl train` arguments of a short pendulum run.
std::vector<std::string> train_args(const std::filesystem::path& run_dir, int num_envs, int n_steps,
                                    std::int64_t total, int batch_size = 64) {
  return {UPKIE_RL_CLI_PATH, "train",
          "--config",        std::string(UPKIE_RL_SOURCE_DIR) + "/configs/pendulum.yaml",
          "--set",           "env.num_envs=" + std::to_string(num_envs),
          "--set",           "env.threads=0",
          "--set",           "ppo.n_steps=" + std::to_string(n_steps),
          "--set",           "ppo.batch_size=" + std::to_string(batch_size),
          "--set",           "ppo.total_timesteps=" + std::to_string(total),
          "--quiet",         "--run-dir",
          run_dir.string()};
}

std::vector<std::string> rank_variables(int rank, int world_size, int port) {
  return {"WORLD_SIZE=" + std::to_string(world_size), "RANK=" + std::to_string(rank),
          "LOCAL_RANK=" + std::to_string(rank), "MASTER_ADDR=127.0.0.1",
          "MASTER_PORT=" + std::to_string(port)};
}

std::string checksum_of(const std::string& output, int rank) {
  std::smatch match;
  const std::regex line("rank " + std::to_string(rank) + ": weights checksum ([0-9a-f]{8})");
  return std::regex_search(output, match, line) ? match[1].str() : "";
}

/// A column of progress.csv.
std::vector<std::string> column(const std::filesystem::path& csv, const std::string& name) {
  std::ifstream in(csv);
  std::string header, line;
  std::getline(in, header);
  std::vector<std::string> names;
  std::stringstream fields(header);
  for (std::string field; std::getline(fields, field, ',');) names.push_back(field);
  const auto index = std::find(names.begin(), names.end(), name) - names.begin();
  std::vector<std::string> values;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string field;
    for (long i = 0; i <= index; ++i) std::getline(row, field, ',');
    values.push_back(field);
  }
  return values;
}

TEST(DistributedTrain, TwoRanksEndWithIdenticalWeightsAndRankZeroAloneWrites) {
  const auto dir0 = temp_path("dist_rank0"), dir1 = temp_path("dist_rank1");
  std::filesystem::remove_all(dir0);
  std::filesystem::remove_all(dir1);
  const int port = free_port();
  Process rank1(train_args(dir1, 2, 256, 2048), "dist_rank1", rank_variables(1, 2, port));
  Process rank0(train_args(dir0, 2, 256, 2048), "dist_rank0", rank_variables(0, 2, port));
  ASSERT_EQ(rank0.wait(), 0) << rank0.output();
  ASSERT_EQ(rank1.wait(), 0) << rank1.output();
  const std::string checksum = checksum_of(rank0.output(), 0);
  ASSERT_EQ(checksum.size(), 8u) << rank0.output();
  EXPECT_EQ(checksum_of(rank1.output(), 1), checksum) << rank1.output();
  EXPECT_NE(rank0.output().find("DD-PPO over 2 ranks: 2 x 2 envs, global n_steps 512, global "
                                "minibatch 128"),
            std::string::npos)
      << rank0.output();
  // Rank 0 counts both ranks' steps: 4 iterations of 2 x 256.
  EXPECT_EQ(column(dir0 / "progress.csv", "time/total_timesteps"),
            (std::vector<std::string>{"512", "1024", "1536", "2048"}));
  EXPECT_FALSE(std::filesystem::exists(dir1)) << "rank 1 writes nothing";
  EXPECT_NE(rank0.output().find("final model"), std::string::npos);
  std::filesystem::remove_all(dir0);
}

// The invariants of the data-parallel run against one process with the environments of
// both ranks: the steps of an iteration, the number of optimiser steps and the learning
// rate schedule are the same; the returns and losses are not (other environments, other
// minibatches).
TEST(DistributedTrain, TwoRanksCountLikeOneProcessWithTwiceTheEnvironments) {
  const auto dir_ranks = temp_path("dist_invariant"), dir_alone = temp_path("alone_invariant");
  std::filesystem::remove_all(dir_ranks);
  std::filesystem::remove_all(dir_alone);
  const int port = free_port();
  {
    Process rank1(train_args(temp_path("unused"), 2, 256, 2048), "inv_rank1",
                  rank_variables(1, 2, port));
    Process rank0(train_args(dir_ranks, 2, 256, 2048), "inv_rank0", rank_variables(0, 2, port));
    ASSERT_EQ(rank0.wait(), 0) << rank0.output();
    ASSERT_EQ(rank1.wait(), 0) << rank1.output();
  }
  Process alone(train_args(dir_alone, 4, 512, 2048, 128), "inv_alone");
  ASSERT_EQ(alone.wait(), 0) << alone.output();
  for (const char* tag : {"time/total_timesteps", "time/iterations", "train/n_updates",
                          "train/learning_rate", "train/clip_range"}) {
    EXPECT_EQ(column(dir_ranks / "progress.csv", tag), column(dir_alone / "progress.csv", tag))
        << tag;
  }
  EXPECT_NE(column(dir_ranks / "progress.csv", "train/value_loss"),
            column(dir_alone / "progress.csv", "train/value_loss"));
  std::filesystem::remove_all(dir_ranks);
  std::filesystem::remove_all(dir_alone);
}

TEST(DistributedTrain, KillingOneRankEndsTheOtherWithAClearErrorAndKeepsItsCheckpoints) {
  const auto dir0 = temp_path("dist_fault");
  std::filesystem::remove_all(dir0);
  const int port = free_port();
  std::vector<std::string> args0 = train_args(dir0, 2, 256, 100'000'000);
  args0.insert(args0.end(), {"--set", "checkpoint_every=1024", "--dist-timeout", "10"});
  std::vector<std::string> args1 = train_args(temp_path("unused"), 2, 256, 100'000'000);
  args1.insert(args1.end(), {"--set", "checkpoint_every=1024", "--dist-timeout", "10"});
  Process rank0(args0, "fault_rank0", rank_variables(0, 2, port));
  Process rank1(args1, "fault_rank1", rank_variables(1, 2, port));
  // Wait for a checkpoint, then kill rank 1.
  const auto checkpoints = dir0 / "checkpoints";
  for (int i = 0;
       i < 600 && (!std::filesystem::exists(checkpoints) || std::filesystem::is_empty(checkpoints));
       ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ASSERT_TRUE(std::filesystem::exists(checkpoints)) << rank0.output();
  rank1.kill();
  const auto killed_at = std::chrono::steady_clock::now();
  const int code = rank0.wait();
  const auto waited = std::chrono::steady_clock::now() - killed_at;
  EXPECT_EQ(code, 1) << rank0.output();
  EXPECT_LT(waited, std::chrono::seconds(60));
  EXPECT_NE(rank0.output().find("upkie-rl: error: rank 0 of 2: sum failed: rank 1 stopped "
                                "answering (no heartbeat for 2.5 s"),
            std::string::npos)
      << rank0.output();
  // The checkpoints written before are whole: a rollout loads the last one.
  std::filesystem::path last;
  for (const auto& entry : std::filesystem::directory_iterator(checkpoints)) {
    if (entry.path().extension() == ".ckpt" && entry.path() > last) last = entry.path();
  }
  ASSERT_FALSE(last.empty());
  const auto rollout = testing::run_cli(
      "rollout --env Upkie-Bullet-Pendulum --max-steps 5 --model " + last.string());
  EXPECT_EQ(rollout.exit_code, 0) << rollout.output;
  std::filesystem::remove_all(dir0);
}

// Resuming from rank 0's checkpoint: with the same world size, the run continues as the
// uninterrupted one did (the same weights at the end, the same logged values); with another
// world size, it continues on the global timestep count (the learning rate schedule and the
// end), with other environments and minibatches.
TEST(DistributedTrain, ResumesWithTheSameOrAnotherWorldSize) {
  const auto whole = temp_path("dist_whole"), again = temp_path("dist_again"),
             alone = temp_path("dist_resumed_alone");
  for (const auto& dir : {whole, again, alone}) std::filesystem::remove_all(dir);
  auto with_checkpoints = [](std::vector<std::string> args) {
    args.insert(args.end(), {"--set", "checkpoint_every=2048"});
    return args;
  };
  std::string uninterrupted;
  {
    const int port = free_port();
    Process rank1(with_checkpoints(train_args(temp_path("unused"), 2, 256, 4096)), "whole_rank1",
                  rank_variables(1, 2, port));
    Process rank0(with_checkpoints(train_args(whole, 2, 256, 4096)), "whole_rank0",
                  rank_variables(0, 2, port));
    ASSERT_EQ(rank0.wait(), 0) << rank0.output();
    ASSERT_EQ(rank1.wait(), 0) << rank1.output();
    uninterrupted = checksum_of(rank0.output(), 0);
  }
  const std::string checkpoint =
      (whole / "checkpoints" / "checkpoint_000002048_steps.ckpt").string();
  ASSERT_TRUE(std::filesystem::exists(checkpoint));
  auto resume_args = [&](const std::filesystem::path& dir) {
    return std::vector<std::string>{UPKIE_RL_CLI_PATH, "train",     "--resume",  checkpoint,
                                    "--quiet",         "--run-dir", dir.string()};
  };
  {
    const int port = free_port();
    Process rank1(resume_args(temp_path("unused")), "again_rank1", rank_variables(1, 2, port));
    Process rank0(resume_args(again), "again_rank0", rank_variables(0, 2, port));
    ASSERT_EQ(rank0.wait(), 0) << rank0.output();
    ASSERT_EQ(rank1.wait(), 0) << rank1.output();
    EXPECT_EQ(checksum_of(rank0.output(), 0), uninterrupted) << rank0.output();
    EXPECT_EQ(checksum_of(rank1.output(), 1), uninterrupted) << rank1.output();
  }
  for (const char* tag : {"time/total_timesteps", "train/value_loss", "rollout/ep_rew_mean"}) {
    const auto whole_values = column(whole / "progress.csv", tag);
    const auto resumed_values = column(again / "progress.csv", tag);
    ASSERT_EQ(resumed_values.size(), 4U) << tag;
    EXPECT_TRUE(std::equal(resumed_values.begin(), resumed_values.end(), whole_values.end() - 4))
        << tag;
  }
  Process resumed_alone(resume_args(alone), "resumed_alone");
  ASSERT_EQ(resumed_alone.wait(), 0) << resumed_alone.output();
  const auto steps = column(alone / "progress.csv", "time/total_timesteps");
  ASSERT_EQ(steps.size(), 8U) << "2,048 more steps, 256 per iteration";
  EXPECT_EQ(steps.front(), "2304");
  EXPECT_EQ(steps.back(), "4096");
  const auto rates = column(alone / "progress.csv", "train/learning_rate");
  const auto whole_rates = column(whole / "progress.csv", "train/learning_rate");
  const auto whole_steps = column(whole / "progress.csv", "time/total_timesteps");
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const auto found = std::find(whole_steps.begin(), whole_steps.end(), steps[i]);
    if (found == whole_steps.end()) continue;
    EXPECT_EQ(rates[i], whole_rates[static_cast<std::size_t>(found - whole_steps.begin())])
        << "the schedule follows the global timesteps, at " << steps[i];
  }
  for (const auto& dir : {whole, again, alone}) std::filesystem::remove_all(dir);
}

/// Two ranks of a long run with checkpoints every 1,024 steps and a `timeout` in seconds, and
/// rank 0's run directory; returns when rank 0 has written a checkpoint.
struct LongRun {
  std::filesystem::path dir0 = temp_path("dist_long");
  std::unique_ptr<Process> rank0, rank1;

  LongRun(const std::string& name, const std::string& timeout) {
    std::filesystem::remove_all(dir0);
    const int port = free_port();
    auto args = [&](const std::filesystem::path& dir) {
      std::vector<std::string> out = train_args(dir, 2, 256, 100'000'000);
      out.insert(out.end(), {"--set", "checkpoint_every=1024", "--dist-timeout", timeout});
      return out;
    };
    rank0 = std::make_unique<Process>(args(dir0), name + "_rank0", rank_variables(0, 2, port));
    rank1 = std::make_unique<Process>(args(temp_path("unused")), name + "_rank1",
                                      rank_variables(1, 2, port));
    const auto checkpoints = dir0 / "checkpoints";
    for (int i = 0; i < 600 && (!std::filesystem::exists(checkpoints) ||
                                std::filesystem::is_empty(checkpoints));
         ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }
  ~LongRun() { std::filesystem::remove_all(dir0); }
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A hung rank (stopped by SIGSTOP: no heartbeat, no collective): the other gives up after
// --dist-timeout naming it; once it runs again it finds the run over and ends by itself.
TEST(DistributedTrain, AHungRankIsNamedAfterTheTimeoutAndEndsWhenItWakes) {
  LongRun run("hung", "4");
  ASSERT_TRUE(std::filesystem::exists(run.dir0 / "checkpoints")) << run.rank0->output();
  ASSERT_EQ(::kill(run.rank1->pid(), SIGSTOP), 0);
  const auto stopped_at = std::chrono::steady_clock::now();
  EXPECT_EQ(run.rank0->wait(), 1) << run.rank0->output();
  const double waited = seconds_since(stopped_at);
  EXPECT_GE(waited, 3.5);
  EXPECT_LT(waited, 30.0);
  EXPECT_NE(run.rank0->output().find("rank 1 stopped answering"), std::string::npos)
      << run.rank0->output();
  ::kill(run.rank1->pid(), SIGCONT);
  const auto woken_at = std::chrono::steady_clock::now();
  EXPECT_EQ(run.rank1->wait(), 1) << run.rank1->output();
  EXPECT_LT(seconds_since(woken_at), 30.0);
  EXPECT_NE(run.rank1->output().find("rank 0 stopped"), std::string::npos) << run.rank1->output();
}

// Rank 0 dies: it served the rendezvous store, and the others say so.
TEST(DistributedTrain, WhenRankZeroDiesTheOthersNameIt) {
  LongRun run("rank0_dies", "10");
  ASSERT_TRUE(std::filesystem::exists(run.dir0 / "checkpoints")) << run.rank0->output();
  run.rank0->kill();
  const auto killed_at = std::chrono::steady_clock::now();
  EXPECT_EQ(run.rank1->wait(), 1) << run.rank1->output();
  EXPECT_LT(seconds_since(killed_at), 30.0);
  EXPECT_NE(run.rank1->output().find("upkie-rl: error: rank 1 of 2: sum failed: rank 0 stopped"),
            std::string::npos)
      << run.rank1->output();
}

/// The command line of torchrun's interpreter, from its first line ("#!/usr/bin/python3.11",
/// "#!/usr/bin/env python3"): the Python that has torch, which python3 on the PATH may not.
std::vector<std::string> torchrun_interpreter() {
  std::string path = testing::shell_output("command -v torchrun");
  path.erase(path.find_last_not_of(" \n") + 1);
  std::ifstream script(path);
  std::string first_line;
  std::getline(script, first_line);
  if (first_line.rfind("#!", 0) != 0) return {"python3"};
  std::vector<std::string> command;
  std::stringstream words(first_line.substr(2));
  for (std::string word; words >> word;) command.push_back(word);
  return command;
}

TEST(DistributedTrain, TorchrunLaunchesIt) {
  if (std::system("command -v torchrun > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "torchrun is not installed (python3-torch); the variables it sets are "
                    "tested above";
  }
  const auto dir = temp_path("dist_torchrun");
  std::filesystem::remove_all(dir);
  std::vector<std::string> args = train_args(dir, 2, 256, 1024);
  // torchrun 1.13 (Debian) knows only the underscore spellings; later ones take both. On
  // Python 3.11 it cannot parse its default "--redirects 0 --tee 0" (Std.from_str returns
  // None for 0), so the output goes through its tee instead.
  args.insert(args.begin(), {"--nproc_per_node", "2", "--master_port", std::to_string(free_port()),
                             "--redirects", "1", "--tee", "1", "--no_python"});
  // torchrun through scripts/torchrun_classic_store.py, run by torchrun's own Python: torchrun
  // unchanged where PyTorch has libuv or predates it (Debian 12's 1.13); where it lacks libuv
  // (Debian 13's 2.6, on which every plain torchrun rendezvous fails), torchrun with the
  // classic store backend, the workaround docs/training.md gives.
  std::vector<std::string> launcher_command = torchrun_interpreter();
  launcher_command.push_back(std::string(UPKIE_RL_SOURCE_DIR) +
                             "/scripts/torchrun_classic_store.py");
  args.insert(args.begin(), launcher_command.begin(), launcher_command.end());
  Process launcher(args, "torchrun");
  ASSERT_EQ(launcher.wait(), 0) << launcher.output();
  const std::string checksum = checksum_of(launcher.output(), 0);
  ASSERT_EQ(checksum.size(), 8u) << launcher.output();
  EXPECT_EQ(checksum_of(launcher.output(), 1), checksum) << launcher.output();
  EXPECT_TRUE(std::filesystem::exists(dir / "progress.csv"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace upkie_rl
