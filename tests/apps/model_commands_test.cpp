/// `upkie-rl export` and `upkie-rl info` from the real binary: provenance recorded by a
/// training and shown for its .ckpt, .pt and ONNX export; old models show "unknown"; bad
/// files are refused with the file named.

#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "apps/cli_runner.hpp"
#include "common/temp_files.hpp"

namespace upkie_rl {
namespace {

using testing::run_cli;
using testing::temp_path;

const std::filesystem::path kPolicies = std::filesystem::path(UPKIE_RL_TEST_DATA_DIR) / "policies";

std::filesystem::path model_file(const std::filesystem::path& run_dir, const std::string& ext) {
  for (const auto& entry : std::filesystem::directory_iterator(run_dir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("model_", 0) == 0 && entry.path().extension() == ext) return entry.path();
  }
  return {};
}

bool has_line(const std::string& output, const std::string& pattern) {
  return std::regex_search(output, std::regex("(^|\n)" + pattern + "(\n|$)"));
}

TEST(ModelCommands, ATrainedModelCarriesItsProvenanceThroughEveryFormat) {
  const auto run_dir = temp_path("provenance_run");
  std::filesystem::remove_all(run_dir);
  const auto trained = run_cli(
      "train --quiet --config " + std::string(UPKIE_RL_SOURCE_DIR) +
      "/configs/pendulum.yaml --seed 5 --run-dir " + run_dir.string() +
      " --set env.num_envs=2 --set env.threads=0 --set ppo.n_steps=64 --set ppo.batch_size=32"
      " --set ppo.n_epochs=1 --set ppo.total_timesteps=128 --set checkpoint_every=0"
      " --set policy.actor_hidden_sizes=[8] --set policy.critic_hidden_sizes=[8]");
  ASSERT_EQ(trained.exit_code, 0) << trained.output;
  const auto onnx = temp_path("provenance.onnx");
  const auto exported =
      run_cli("export " + model_file(run_dir, ".ckpt").string() + " --onnx " + onnx.string());
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  for (const auto& model : {model_file(run_dir, ".ckpt"), model_file(run_dir, ".pt"), onnx}) {
    const auto info = run_cli("info " + model.string());
    ASSERT_EQ(info.exit_code, 0) << info.output;
    EXPECT_TRUE(has_line(info.output, "git_commit: ([0-9a-f]{40}(-dirty)?|unknown)"))
        << info.output;
    EXPECT_TRUE(has_line(info.output, "upkie_rl_version: [0-9]+\\.[0-9]+\\.[0-9]+")) << info.output;
    EXPECT_TRUE(has_line(info.output, "date: 20[0-9-]+T[0-9:]+Z")) << info.output;
    EXPECT_TRUE(has_line(info.output, "source: upkie-rl train")) << info.output;
    EXPECT_TRUE(has_line(info.output, "env_id: Upkie-Bullet-Pendulum")) << info.output;
    EXPECT_TRUE(has_line(info.output, "seed: 5")) << info.output;
    EXPECT_TRUE(has_line(info.output, "timesteps: 128")) << info.output;
    EXPECT_TRUE(has_line(info.output, "  ppo:")) << info.output;  // The training config.
  }
  std::filesystem::remove_all(run_dir);
}

TEST(ModelCommands, AnOldModelShowsUnknownWhereItCannotSay) {
  const auto info = run_cli("info " + (kPolicies / "pendulum_mujoco_seed0.ckpt").string());
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_TRUE(has_line(info.output, "git_commit: unknown")) << info.output;
  EXPECT_TRUE(has_line(info.output, "date: unknown")) << info.output;
  EXPECT_TRUE(has_line(info.output, "env_id: Upkie-MuJoCo-Pendulum")) << info.output;
  EXPECT_TRUE(has_line(info.output, "observation_space: 4: theta, p, theta_dot, p_dot"))
      << info.output;
}

TEST(ModelCommands, TheOnnxExportShowsItsInterfaceAndMetadata) {
  const auto onnx = temp_path("servos.onnx");
  const auto exported =
      run_cli("export " + (kPolicies / "servos_balance_mujoco_seed0.ckpt").string() + " --onnx " +
              onnx.string());
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  const auto info = run_cli("info " + onnx.string());
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_TRUE(has_line(info.output, "input: observation FLOAT \\[batch, [0-9]+\\]")) << info.output;
  EXPECT_TRUE(has_line(info.output, "output: action FLOAT \\[batch, [0-9]+\\]")) << info.output;
  EXPECT_TRUE(has_line(info.output, "frequency: [0-9.]+")) << info.output;
}

TEST(ModelCommands, BadFilesAreRefusedWithTheirName) {
  const auto text = temp_path("not_a_model.onnx");
  testing::write_bytes(text, "hello");
  auto result = run_cli("info " + text.string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("not_a_model.onnx: not an ONNX model"), std::string::npos)
      << result.output;
  const auto fake_pt = temp_path("fake.pt");
  testing::write_bytes(fake_pt, "PK\x03\x04 truncated zip");
  result = run_cli("info " + fake_pt.string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("fake.pt"), std::string::npos) << result.output;
  // An activation nobody knows is refused by key, with the list of the known ones.
  result = run_cli("train --config " + std::string(UPKIE_RL_SOURCE_DIR) +
                   "/configs/pendulum.yaml --set policy.activation=swish --run-dir " +
                   temp_path("swish_run").string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("policy.activation"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("relu, tanh, elu"), std::string::npos) << result.output;
  const auto bad_ckpt = temp_path("bad.ckpt");
  testing::write_bytes(bad_ckpt, "UPKIERL1");
  result = run_cli("export " + bad_ckpt.string() + " --onnx " + temp_path("x.onnx").string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("bad.ckpt"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace upkie_rl
