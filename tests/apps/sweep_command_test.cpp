/// `upkie-rl sweep` from the real binary: a local sweep with its summary and figure, the same
/// run launched alone (as a cluster task would), continuing after failures and interruptions,
/// and bad arguments.

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "apps/cli_runner.hpp"
#include "common/background_process.hpp"
#include "common/shell_output.hpp"
#include "common/temp_files.hpp"

namespace upkie_rl {
namespace {

using testing::read_bytes;
using testing::run_cli;
using testing::temp_path;
using testing::write_bytes;

/// Arguments of a small sweep of pendulum runs (2,048 steps each) into `directory`.
std::string small_sweep(const std::filesystem::path& directory, std::int64_t timesteps = 2048) {
  return "sweep --config " + std::string(UPKIE_RL_SOURCE_DIR) +
         "/configs/pendulum.yaml --seeds 0:2 --set ppo.n_epochs=2,3 --set env.num_envs=2 --set "
         "env.threads=0 --set ppo.n_steps=512 --set ppo.batch_size=64 --set "
         "ppo.total_timesteps=" +
         std::to_string(timesteps) + " --set checkpoint_every=1024 --eval-episodes 2 --output " +
         directory.string();
}

nlohmann::json evaluation_of(const std::filesystem::path& run_dir) {
  return nlohmann::json::parse(read_bytes(run_dir / "evaluation.json"));
}

std::size_t count_lines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST(SweepCommand, RunsTheGridHereThenSummarisesAndFigures) {
  const auto directory = temp_path("sweep_local");
  std::filesystem::remove_all(directory);
  const auto result = run_cli(small_sweep(directory) + " --jobs 2");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const char* names[] = {"n_epochs=2_seed0", "n_epochs=2_seed1", "n_epochs=3_seed0",
                         "n_epochs=3_seed1"};
  for (const char* name : names) {
    const auto run_dir = directory / "runs" / name;
    const nlohmann::json evaluation = evaluation_of(run_dir);
    EXPECT_GE(evaluation["timesteps"].get<std::int64_t>(), 2048) << name;
    EXPECT_EQ(evaluation["evaluation"]["episodes"].get<int>(), 2) << name;
    EXPECT_TRUE(std::filesystem::exists(run_dir / evaluation["model"].get<std::string>()));
    EXPECT_TRUE(std::filesystem::exists(directory / "logs" / (std::string(name) + ".log")));
    EXPECT_NE(result.output.find(std::string("done ") + name), std::string::npos);
  }
  // The n_epochs values reached the runs' configurations.
  EXPECT_NE(read_bytes(directory / "runs" / names[2] / "config.yaml").find("n_epochs: 3"),
            std::string::npos);
  const std::string csv = read_bytes(directory / "summary.csv");
  EXPECT_EQ(count_lines(csv), 5U) << csv;
  EXPECT_EQ(csv.find("pending"), std::string::npos) << csv;
  const std::string markdown = read_bytes(directory / "summary.md");
  EXPECT_NE(markdown.find("| ppo.n_epochs=2 | 2 of 2 |"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("| ppo.n_epochs=3 | 2 of 2 |"), std::string::npos) << markdown;
  EXPECT_EQ(read_bytes(directory / "returns.png").substr(1, 3), "PNG");

  // Again: nothing left to train, the summary is the same.
  const auto again = run_cli("sweep " + directory.string());
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("all 4 runs of"), std::string::npos) << again.output;
  EXPECT_EQ(read_bytes(directory / "summary.csv"), csv);

  // A run launched alone, as a cluster task, gives what the local launcher gave: the same
  // seed and thread counts give the same run.
  const auto alone = temp_path("sweep_alone");
  std::filesystem::remove_all(alone);
  const auto planned = run_cli(small_sweep(alone) + " --plan");
  ASSERT_EQ(planned.exit_code, 0) << planned.output;
  EXPECT_FALSE(std::filesystem::exists(alone / "runs"));
  EXPECT_NE(planned.output.find("--run I   (I = 0..3)"), std::string::npos) << planned.output;
  const auto task = run_cli("sweep " + alone.string() + " --run 2");
  ASSERT_EQ(task.exit_code, 0) << task.output;
  const nlohmann::json local = evaluation_of(directory / "runs" / names[2]);
  const nlohmann::json single = evaluation_of(alone / "runs" / names[2]);
  EXPECT_EQ(single["evaluation"], local["evaluation"]);
  EXPECT_EQ(single["training_mean_return"], local["training_mean_return"]);
  const auto summary = run_cli("sweep " + alone.string() + " --summary");
  EXPECT_EQ(summary.exit_code, 0) << summary.output;
  EXPECT_NE(read_bytes(alone / "summary.md").find("| ppo.n_epochs=3 | 1 of 2 |"),
            std::string::npos);
  EXPECT_NE(read_bytes(alone / "summary.csv").find("pending"), std::string::npos);
}

TEST(SweepCommand, AStoppedRunResumesFromItsLastCheckpointAndEndsTheSame) {
  const auto directory = temp_path("sweep_resume");
  std::filesystem::remove_all(directory);
  ASSERT_EQ(run_cli(small_sweep(directory, 3072) + " --plan").exit_code, 0);
  ASSERT_EQ(run_cli("sweep " + directory.string() + " --run 0").exit_code, 0);
  const auto run_dir = directory / "runs" / "n_epochs=2_seed0";
  const nlohmann::json uninterrupted = evaluation_of(run_dir);
  // As if it had stopped after its checkpoint at 2,048 steps.
  std::filesystem::remove(run_dir / "evaluation.json");
  for (const auto& entry : std::filesystem::directory_iterator(run_dir)) {
    if (entry.path().filename().string().rfind("model_", 0) == 0)
      std::filesystem::remove(entry.path());
  }
  std::filesystem::remove(run_dir / "checkpoints" / "checkpoint_000003072_steps.ckpt");
  ASSERT_TRUE(std::filesystem::exists(run_dir / "checkpoints" / "checkpoint_000002048_steps.ckpt"));
  const auto resumed = run_cli("sweep " + directory.string() + " --run 0");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming"), std::string::npos) << resumed.output;
  EXPECT_EQ(evaluation_of(run_dir)["evaluation"], uninterrupted["evaluation"]);
}

TEST(SweepCommand, AFailedRunIsReportedTheOthersFinishAndNothingIsLost) {
  const auto directory = temp_path("sweep_failure");
  std::filesystem::remove_all(directory);
  ASSERT_EQ(run_cli(small_sweep(directory) + " --plan").exit_code, 0);
  // A damaged checkpoint in run 1: resuming it fails.
  const auto damaged = directory / "runs" / "n_epochs=2_seed1" / "checkpoints";
  std::filesystem::create_directories(damaged);
  write_bytes(damaged / "checkpoint_000001024_steps.ckpt", "not a checkpoint");
  const auto result = run_cli("sweep " + directory.string() + " --jobs 2");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("FAILED n_epochs=2_seed1 (exit 1)"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("1 run failed"), std::string::npos) << result.output;
  EXPECT_EQ(read_bytes(damaged / "checkpoint_000001024_steps.ckpt"), "not a checkpoint");
  const std::string csv = read_bytes(directory / "summary.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5) << csv;
  EXPECT_NE(csv.find("n_epochs=2_seed1,1,ppo.n_epochs=2,pending"), std::string::npos) << csv;
  for (const char* name : {"n_epochs=2_seed0", "n_epochs=3_seed0", "n_epochs=3_seed1"}) {
    EXPECT_TRUE(std::filesystem::exists(directory / "runs" / name / "evaluation.json")) << name;
  }
}

TEST(SweepCommand, SigtermStopsTheRunsAndLeavesNoProcess) {
  const auto directory = temp_path("sweep_interrupted");
  std::filesystem::remove_all(directory);
  ASSERT_EQ(run_cli(small_sweep(directory, 2'000'000) + " --plan").exit_code, 0);
  testing::BackgroundProcess sweep({UPKIE_RL_CLI_PATH, "sweep", directory.string(), "--jobs", "2"},
                                   "sweep_interrupted");
  const auto log = directory / "logs" / "n_epochs=2_seed1.log";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (read_bytes(log).find("training") == std::string::npos &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ASSERT_NE(read_bytes(log).find("training"), std::string::npos);
  EXPECT_EQ(sweep.wait(SIGTERM), 1);
  EXPECT_NE(sweep.output().find("interrupted: stopping 2 runs"), std::string::npos)
      << sweep.output();
  // "[s]weep": the pattern does not match the shell that runs pgrep.
  const auto children =
      testing::shell_output("pgrep -f '[s]weep " + directory.string() + " --run'");
  EXPECT_EQ(children, "") << "runs left running";
}

TEST(SweepCommand, BadArgumentsAreRefusedWithAReason) {
  const std::string config = std::string(UPKIE_RL_SOURCE_DIR) + "/configs/pendulum.yaml";
  const auto directory = temp_path("sweep_bad");
  std::filesystem::remove_all(directory);
  struct Case {
    std::string arguments;
    std::string reason;
  };
  const Case cases[] = {
      {"sweep --config " + config + " --output " + directory.string(), "needs --seeds"},
      {"sweep --config " + config + " --seeds 0:2 --set ppo.n_epochs=2,0 --output " +
           directory.string(),
       "sweep run n_epochs=0_seed0: config key 'ppo.n_epochs'"},
      {"sweep --config " + config + " --seeds 2:1 --output " + directory.string(), "seeds '2:1'"},
      {"sweep " + directory.string(), "sweep.yaml: cannot read"},
      {"sweep --config " + config + " --seeds 0 --run 0", "--run and --summary take"},
      {"sweep", "either --config"},
  };
  for (const Case& bad : cases) {
    const auto result = run_cli(bad.arguments);
    EXPECT_EQ(result.exit_code, 1) << bad.arguments << "\n" << result.output;
    EXPECT_NE(result.output.find(bad.reason), std::string::npos) << result.output;
  }
  EXPECT_FALSE(std::filesystem::exists(directory)) << "a refused sweep wrote its directory";
}

}  // namespace
}  // namespace upkie_rl
