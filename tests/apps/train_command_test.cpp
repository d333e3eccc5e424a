#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "apps/cli_runner.hpp"
#include "common/shell_output.hpp"

namespace upkie_rl {
namespace {

using testing::run_cli;

std::filesystem::path fresh_directory(const std::string& name) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("upkie_rl_cli_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(path);
  return path;
}

const std::string kConfig = std::string(UPKIE_RL_SOURCE_DIR) + "/configs/pendulum.yaml";
const std::string kTiny =
    " --set env.num_envs=2 --set env.threads=0 --set ppo.n_steps=64 --set ppo.batch_size=32"
    " --set ppo.n_epochs=1 --set ppo.total_timesteps=256 --set checkpoint_every=128"
    " --set policy.actor_hidden_sizes=[8] --set policy.critic_hidden_sizes=[8]";

std::filesystem::path find_model(const std::filesystem::path& run_dir) {
  for (const auto& entry : std::filesystem::directory_iterator(run_dir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("model_", 0) == 0 && entry.path().extension() == ".ckpt") return entry.path();
  }
  return {};
}

/// What `upkie-rl train` draws on a 60-column terminal: run in a pseudo-terminal by
/// `script`, after `stty cols 60`.
std::string train_in_a_terminal(const std::filesystem::path& run_dir) {
  const std::string train = std::string(UPKIE_RL_CLI_PATH) + " train --config " + kConfig + kTiny +
                            " --set ppo.total_timesteps=1024 --run-dir " + run_dir.string();
  return testing::shell_output("script -qec 'stty cols 60 rows 24; " + train + "' /dev/null 2>&1");
}

TEST(TrainCommand, ProgressFitsA60ColumnTerminalAndIsPlainLinesInAFile) {
  const auto run_dir = fresh_directory("progress_tty");
  const std::string terminal = train_in_a_terminal(run_dir);
  // Each redraw starts with a carriage return and ends by clearing the rest of the line;
  // none may be wider than 59 columns (it would wrap onto a new line at every update).
  int redraws = 0;
  std::size_t start = 0;
  while ((start = terminal.find('\r', start)) != std::string::npos) {
    if (terminal.compare(start, 2, "\r\n") == 0) {  // the terminal's line ending
      start += 2;
      continue;
    }
    std::size_t end = terminal.find("\x1b[K", start);
    if (end == std::string::npos) break;
    const std::string line = terminal.substr(start + 1, end - start - 1);
    start = end;
    if (line.find("steps") == std::string::npos) continue;
    ++redraws;
    EXPECT_LE(line.size(), 59u) << "\"" << line << "\"";
    EXPECT_EQ(line.find('\n'), std::string::npos) << line;
  }
  EXPECT_GE(redraws, 4) << terminal;
  std::filesystem::remove_all(run_dir);

  // Not a terminal: plain periodic lines, no carriage return or escape sequence.
  const auto file_run_dir = fresh_directory("progress_file");
  const auto result = run_cli("train --config " + kConfig + kTiny +
                              " --set ppo.total_timesteps=1024 --run-dir " + file_run_dir.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(result.output.find('\r'), std::string::npos);
  EXPECT_EQ(result.output.find('\x1b'), std::string::npos);
  EXPECT_NE(result.output.find("100% 1,024/1,024 steps | return"), std::string::npos)
      << result.output;
  std::filesystem::remove_all(file_run_dir);
}

TEST(TrainCommand, TrainsEvaluatesAndResumesFromTheCommandLine) {
  const auto run_dir = fresh_directory("train");
  const auto result =
      run_cli("train --quiet --config " + kConfig + kTiny + " --run-dir " + run_dir.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("final model: "), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("time: environments"), std::string::npos) << result.output;
  // One process: no all-reduces to time (a distributed run prints them).
  EXPECT_EQ(result.output.find("all-reduces"), std::string::npos) << result.output;
  EXPECT_TRUE(std::filesystem::exists(run_dir / "config.yaml"));
  EXPECT_TRUE(std::filesystem::exists(run_dir / "progress.csv"));
  const auto checkpoint = run_dir / "checkpoints" / "checkpoint_000000128_steps.ckpt";
  EXPECT_TRUE(std::filesystem::exists(checkpoint));
  const std::filesystem::path model = find_model(run_dir);
  ASSERT_FALSE(model.empty());
  std::filesystem::path torchscript = model;
  EXPECT_TRUE(std::filesystem::exists(torchscript.replace_extension(".pt")));

  // The resolved config records the overrides.
  std::ifstream config(run_dir / "config.yaml");
  const std::string text((std::istreambuf_iterator<char>(config)),
                         std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("total_timesteps: 256"), std::string::npos) << text;

  // Deterministic evaluation of the saved model.
  const auto rollout = run_cli(
      "rollout --env Upkie-Bullet-Pendulum --episodes 2 --max-steps 50 "
      "--model " +
      model.string());
  EXPECT_EQ(rollout.exit_code, 0) << rollout.output;
  EXPECT_NE(rollout.output.find("mean return"), std::string::npos) << rollout.output;

  // A model does not run an environment of other spaces.
  const auto wrong =
      run_cli("rollout --env Upkie-Bullet-ServosTask --episodes 1 --model " + model.string());
  EXPECT_EQ(wrong.exit_code, 1);
  EXPECT_NE(wrong.output.find("does not fit"), std::string::npos) << wrong.output;

  // Resume from the checkpoint.
  const auto resumed = run_cli("train --quiet --resume " + checkpoint.string());
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming"), std::string::npos) << resumed.output;
  std::filesystem::remove_all(run_dir);
}

TEST(TrainCommand, BadInputGivesClearErrors) {
  const auto run_dir = fresh_directory("bad");
  auto result = run_cli("train --config " + kConfig + " --set ppo.batch_sise=3 --run-dir " +
                        run_dir.string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("unknown config key 'ppo.batch_sise'"), std::string::npos)
      << result.output;

  result =
      run_cli("train --config " + kConfig + " --set ppo.gamma=high --run-dir " + run_dir.string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("ppo.gamma"), std::string::npos) << result.output;

  std::filesystem::create_directories(run_dir);
  const auto broken = run_dir / "broken.yaml";
  std::ofstream(broken) << "ppo:\n  n_epochs: [\n";
  result = run_cli("train --config " + broken.string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("malformed YAML"), std::string::npos) << result.output;

  const auto checkpoint = run_dir / "damaged.ckpt";
  std::ofstream(checkpoint) << "UPKIERL1 truncated";
  result = run_cli("train --resume " + checkpoint.string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("damaged.ckpt"), std::string::npos) << result.output;

  result = run_cli("rollout --env Upkie-Bullet-Pendulum --model " + checkpoint.string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("damaged.ckpt"), std::string::npos) << result.output;

  result = run_cli("train --config " + kConfig + " --resume " + checkpoint.string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("cannot be combined"), std::string::npos) << result.output;
  std::filesystem::remove_all(run_dir);
}

}  // namespace
}  // namespace upkie_rl
