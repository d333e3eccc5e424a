// Fault injection (issue 26) through the real command line: each case ends with an exit
// status in 1..127, within seconds, with a short message naming the culprit, and leaves
// existing files intact.

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "apps/clean_refusal.hpp"
#include "apps/cli_runner.hpp"
#include "common/temp_files.hpp"
#include "policy/checkpoint_file.hpp"
#include "policy/checkpoint_gate.hpp"

namespace upkie_rl {
namespace {

using testing::expect_clean_refusal;
using testing::run_cli;

const std::string kConfig = std::string(UPKIE_RL_SOURCE_DIR) + "/configs/pendulum.yaml";
const std::filesystem::path kModel =
    std::filesystem::path(UPKIE_RL_SOURCE_DIR) / "tests/data/policies/pendulum_bullet_seed0.ckpt";

TEST(ReliabilityCli, UnboundedSettingsAreRefusedBeforeAnythingStarts) {
  const std::filesystem::path run_dir = testing::temp_path("never_made", "upkie_rl_cli_bounds");
  for (const auto& [setting, culprit] : std::vector<std::pair<std::string, std::string>>{
           {"ppo.n_steps=2000000000000", "'ppo.n_steps': 2000000000000"},
           {"policy.actor_hidden_sizes=[300000]", "'policy.actor_hidden_sizes': 300000"},
           {"torch_threads=20000", "'torch_threads': 20000"},
           {"env.num_envs=3000000", "'env.num_envs': 3000000"},
           {"ppo.ent_coef=nan", "'ppo.ent_coef': nan"},
           {"policy.log_std_init=inf", "'policy.log_std_init': inf"},
           {"normalize.epsilon=1e39", "'normalize.epsilon': 1e+39"},
           {"ppo.learning_rate_initial=1e39", "'ppo.learning_rate_initial': 1e+39"}}) {
    expect_clean_refusal("train --quiet --config " + kConfig + " --set " + setting + " --run-dir " +
                             run_dir.string(),
                         culprit);
  }
  EXPECT_FALSE(std::filesystem::exists(run_dir));
}

TEST(ReliabilityCli, NonFiniteFlagsAndEmptyPathsAreRefused) {
  expect_clean_refusal("train --config " + kConfig + " --dist-timeout nan", "--dist-timeout");
  expect_clean_refusal("rollout --env Upkie-Bullet-Pendulum --episodes 1 --record ''", "--record");
  expect_clean_refusal("rollout --env Upkie-Bullet-Pendulum --episodes 1 --video ''", "--video");
  expect_clean_refusal("spine --spine-frequency inf", "--spine-frequency");
  expect_clean_refusal("spine --shm-mode 0777", "--shm-mode");
}

// Issue 26: NaN passed CLI::Range and CLI::NonNegativeNumber, and --push-force had no
// bound at all; each of these ran a spine (NaN pushes failing only at push time).
TEST(ReliabilityCli, SpineNumbersMustBeFiniteAndBounded) {
  const std::string name = "/upkie_rl_cli_spine_flags_" + std::to_string(::getpid());
  for (const auto& [flag, value] :
       std::vector<std::pair<std::string, std::string>>{{"--push-force", "nan"},
                                                        {"--push-force", "inf"},
                                                        {"--push-force", "1e39"},
                                                        {"--push-force", "-1e12"},
                                                        {"--push-force", "501"},
                                                        {"--push-time", "nan"},
                                                        {"--push-time", "-1"},
                                                        {"--push-duration", "nan"},
                                                        {"--push-duration", "1e308"},
                                                        {"--observation-latency", "nan"},
                                                        {"--cycle-jitter", "nan"},
                                                        {"--action-delay", "nan"},
                                                        {"--action-lag", "-1"},
                                                        {"--action-lag", "1e308"},
                                                        {"--physics-option", "payload_mass=1e308"}}) {
    const testing::CliResult result = expect_clean_refusal(
        "spine --shm-name " + name + " --nb-substeps 1 " + flag + " " + value, flag);
    EXPECT_LT(result.output.size(), 300u) << result.output;  // no 300-digit DBL_MAX
  }
  // A mistyped option name gets the nearest one suggested (and the valid ones listed).
  const testing::CliResult mistyped = expect_clean_refusal(
      "spine --shm-name " + name + " --nb-substeps 1 --physics-option payload_mas=1",
      "--physics-option");
  EXPECT_NE(mistyped.output.find("did you mean \"payload_mass\"?"), std::string::npos)
      << mistyped.output;
  EXPECT_FALSE(std::filesystem::exists("/dev/shm" + name));
  const testing::CliResult help = run_cli("spine --help", 60);
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_EQ(help.output.find("17976931348623157"), std::string::npos) << help.output;
  EXPECT_NE(help.output.find("[-500, 500]"), std::string::npos) << help.output;
}

// Issue 26: a spine replaced any unlocked object of its name, then unlinked it at exit.
TEST(ReliabilityCli, SpineRefusesAnotherProgramsSharedMemoryObject) {
  const std::string name = "/upkie_rl_cli_foreign_" + std::to_string(::getpid());
  const std::filesystem::path path = "/dev/shm" + name;
  std::ofstream(path) << "data\n";
  expect_clean_refusal("spine --shm-name " + name + " --nb-substeps 1", "rm " + path.string());
  std::ifstream file(path);
  const std::string bytes{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  EXPECT_EQ(bytes, "data\n");
  std::filesystem::remove(path);
}

TEST(ReliabilityCli, EveryReaderRefusesACraftedCheckpointWithTheSameMessage) {
  CheckpointFile file = read_checkpoint_file(kModel);
  file.header["version"] = 2;
  const std::filesystem::path crafted = testing::temp_path("v2.ckpt", "upkie_rl_cli_gate");
  write_checkpoint_file(file, crafted);
  const std::string message = "checkpoint " + crafted.string() +
                              ": checkpoint version 2 is not the version 1 this build reads";
  expect_clean_refusal(
      "rollout --env Upkie-Bullet-Pendulum --episodes 1 --model " + crafted.string(), message);
  expect_clean_refusal(
      "evaluate --env Upkie-Bullet-Pendulum --episodes 1 --model " + crafted.string(), message);
  expect_clean_refusal("train --quiet --resume " + crafted.string(), message);
  const std::string onnx = testing::temp_path("never.onnx", "upkie_rl_cli_gate").string();
  expect_clean_refusal("export " + crafted.string() + " --onnx " + onnx, message);
  expect_clean_refusal("info " + crafted.string(), message);
  EXPECT_FALSE(std::filesystem::exists(onnx));
}

TEST(ReliabilityCli, ExportAndInfoRefuseNanWeightsAndABrokenChecksumThroughTheGate) {
  CheckpointFile file = read_checkpoint_file(kModel);
  file.tensors.at("policy.parameters").values.at(3) = std::numeric_limits<float>::quiet_NaN();
  const std::filesystem::path nan_weights =
      testing::temp_path("nan_weights.ckpt", "upkie_rl_cli_gate");
  write_checkpoint_file(file, nan_weights);
  const std::string onnx = testing::temp_path("never.onnx", "upkie_rl_cli_gate").string();
  const std::string nan_message =
      "checkpoint " + nan_weights.string() + ": tensor 'policy.parameters' value 3 is nan";
  expect_clean_refusal("export " + nan_weights.string() + " --onnx " + onnx, nan_message);
  expect_clean_refusal("info " + nan_weights.string(), nan_message);
  std::string bytes = testing::read_bytes(kModel);
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x01);
  const std::filesystem::path flipped = testing::temp_path("flipped.ckpt", "upkie_rl_cli_gate");
  testing::write_bytes(flipped, bytes);
  // What read_checked_checkpoint says of it, word for word, from every command.
  std::string gate_message;
  try {
    read_checked_checkpoint(flipped);
  } catch (const CheckpointError& error) {
    gate_message = error.what();
  }
  ASSERT_NE(gate_message.find("flipped.ckpt"), std::string::npos) << gate_message;
  expect_clean_refusal("export " + flipped.string() + " --onnx " + onnx, gate_message);
  expect_clean_refusal("info " + flipped.string(), gate_message);
  expect_clean_refusal(
      "rollout --env Upkie-Bullet-Pendulum --episodes 1 --model " + flipped.string(), gate_message);
  EXPECT_FALSE(std::filesystem::exists(onnx));
}

}  // namespace
}  // namespace upkie_rl
