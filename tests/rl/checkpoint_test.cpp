#include "rl/runs/checkpoint.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "common/normalization_state.hpp"
#include "common/temp_files.hpp"
#include "policy/deployed_policy.hpp"
#include "rl/point_mass_vector_env.hpp"
#include "rl/runs/ppo_checkpoint.hpp"

namespace upkie_rl {
namespace {

using testing::read_bytes;
using testing::write_bytes;

std::filesystem::path temp_path(const std::string& name) {
  return testing::temp_path(name, "upkie_rl_checkpoint");
}

using testing::PointMassVectorEnv;

void expect_checkpoint_error(const std::filesystem::path& path, const std::string& text) {
  try {
    load_checkpoint(path);
    FAIL() << "expected a CheckpointError mentioning '" << text << "'";
  } catch (const CheckpointError& error) {
    EXPECT_NE(std::string(error.what()).find(text), std::string::npos) << error.what();
  }
}

TrainingConfig small_config() {
  TrainingConfig config;
  config.env_id = "point-mass";
  config.num_envs = 2;
  config.policy.actor_hidden_sizes = {8};
  config.policy.critic_hidden_sizes = {8};
  config.ppo.total_timesteps = 1000;
  config.ppo.n_steps = 64;
  config.ppo.batch_size = 16;
  config.ppo.n_epochs = 2;
  config.seed = 11;
  return config;
}

TEST(Checkpoint, RoundTripKeepsHeaderAndTensors) {
  // A trainer's checkpoint (the gate refuses anything else), plus a header key and a
  // tensor of our own: both must come back unchanged.
  PointMassVectorEnv env(2);
  Ppo ppo(env, small_config());
  Checkpoint checkpoint = make_ppo_checkpoint(ppo, nullptr);
  checkpoint.header["answer"] = 42;
  checkpoint.tensors["extra"] = torch::arange(6, torch::kFloat32).view({2, 3});
  const auto path = temp_path("round_trip.ckpt");
  save_checkpoint(checkpoint, path);
  const Checkpoint loaded = load_checkpoint(path);
  EXPECT_EQ(loaded.header.at("answer"), 42);
  EXPECT_EQ(loaded.header.at("config"), checkpoint.header.at("config"));
  EXPECT_EQ(loaded.header.at("policy"), checkpoint.header.at("policy"));
  const std::int64_t parameter_count = ppo.policy().flat_parameters().numel();
  EXPECT_TRUE(torch::equal(loaded.tensor("policy.parameters", parameter_count),
                           checkpoint.tensors["policy.parameters"]));
  EXPECT_TRUE(torch::equal(loaded.tensor("extra").view({2, 3}), checkpoint.tensors["extra"]));
  EXPECT_THROW(loaded.tensor("missing"), CheckpointError);
  EXPECT_THROW(loaded.tensor("extra", 5), CheckpointError);
  // No temporary file is left behind.
  for (const auto& entry : std::filesystem::directory_iterator(path.parent_path())) {
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path();
  }
}

TEST(Checkpoint, CorruptedTruncatedAndForeignFilesGiveClearErrors) {
  Checkpoint checkpoint;
  checkpoint.header = {{"k", 1}};
  checkpoint.tensors["w"] = torch::ones({100});
  const auto path = temp_path("bad.ckpt");
  save_checkpoint(checkpoint, path);
  const std::string bytes = read_bytes(path);

  std::string corrupted = bytes;
  corrupted[bytes.size() / 2] ^= 0x10;
  write_bytes(path, corrupted);
  expect_checkpoint_error(path, "CRC");

  for (const std::size_t keep :
       {bytes.size() - 1, bytes.size() / 2, std::size_t{10}, std::size_t{3}, std::size_t{0}}) {
    write_bytes(path, bytes.substr(0, keep));
    EXPECT_THROW(load_checkpoint(path), CheckpointError) << "kept " << keep << " bytes";
  }
  write_bytes(path, "model weights, honest");
  expect_checkpoint_error(path, "not an upkie-rl checkpoint");
  expect_checkpoint_error(temp_path("missing.ckpt"), "cannot open");
}

TEST(PpoCheckpoint, ResumedLearnerContinuesExactlyLikeTheOriginal) {
  const TrainingConfig config = small_config();
  PointMassVectorEnv env_a(2);
  Ppo original(env_a, config);
  original.reset_environments(5);
  for (int i = 0; i < 3; ++i) original.iterate();
  const auto path = temp_path("resume.ckpt");
  save_checkpoint(make_ppo_checkpoint(original, nullptr), path);

  PointMassVectorEnv env_b(2);
  TrainingConfig other_seed = config;
  other_seed.seed = 999;  // different initial weights and random state: all must be restored
  Ppo resumed(env_b, other_seed);
  restore_ppo_checkpoint(resumed, load_checkpoint(path));
  EXPECT_TRUE(
      torch::equal(resumed.policy().flat_parameters(), original.policy().flat_parameters()));
  EXPECT_TRUE(torch::equal(resumed.optimizer().exp_avg_sq(), original.optimizer().exp_avg_sq()));
  EXPECT_EQ(resumed.num_timesteps(), original.num_timesteps());
  EXPECT_EQ(resumed.optimizer().step_count(), original.optimizer().step_count());
  EXPECT_EQ(resumed.episodes().total_episodes(), original.episodes().total_episodes());

  // Both start fresh episodes with the same seed (as the trainer does after a checkpoint)
  // and must then produce identical updates.
  original.reset_environments(77);
  resumed.reset_environments(77);
  for (int i = 0; i < 3; ++i) {
    const PpoUpdateStatistics a = original.iterate();
    const PpoUpdateStatistics b = resumed.iterate();
    EXPECT_EQ(a.loss, b.loss);
    EXPECT_EQ(a.learning_rate, b.learning_rate);
  }
  EXPECT_TRUE(
      torch::equal(resumed.policy().flat_parameters(), original.policy().flat_parameters()));
  EXPECT_EQ(resumed.episodes().mean_return(), original.episodes().mean_return());
}

TEST(PpoCheckpoint, MismatchedPolicyOrSpacesAreRefused) {
  const TrainingConfig config = small_config();
  PointMassVectorEnv env(2);
  Ppo ppo(env, config);
  const Checkpoint checkpoint = make_ppo_checkpoint(ppo, nullptr);

  TrainingConfig wider = config;
  wider.policy.actor_hidden_sizes = {16};
  Ppo other(env, wider);
  try {
    restore_ppo_checkpoint(other, checkpoint);
    FAIL() << "a policy of another shape must be refused";
  } catch (const CheckpointError& error) {
    EXPECT_NE(std::string(error.what()).find("policy"), std::string::npos) << error.what();
  }

  Checkpoint renamed = checkpoint;
  renamed.header["observation_space"]["names"] = {"theta"};
  try {
    restore_ppo_checkpoint(ppo, renamed);
    FAIL() << "a different observation space must be refused";
  } catch (const CheckpointError& error) {
    EXPECT_NE(std::string(error.what()).find("theta"), std::string::npos) << error.what();
  }
}

// The torch-free DeployedPolicy reads what the trainer writes and acts like its torch actor.
TEST(DeployedPolicy, ActsWithTheMeanClippedAndChecksSpaces) {
  const TrainingConfig config = small_config();
  PointMassVectorEnv env(2);
  Ppo ppo(env, config);
  ppo.reset_environments(0);
  ppo.iterate();
  const auto path = temp_path("saved.ckpt");
  save_checkpoint(make_ppo_checkpoint(ppo, testing::normalization_state({0.5}, {4.0}, 10.0)), path);
  DeployedPolicy saved = DeployedPolicy::load(path);
  EXPECT_EQ(saved.env_id(), "point-mass");
  const float observation = 1.3f;
  float action = 0.0f;
  saved.act(std::span<const float>(&observation, 1), std::span<float>(&action, 1));
  const float normalized = static_cast<float>((1.3 - 0.5) / std::sqrt(4.0 + 1e-8));
  const float mean = ppo.policy().action_mean(torch::tensor({{normalized}})).item<float>();
  EXPECT_NEAR(action, std::clamp(mean, -1.0f, 1.0f), 1e-6);
  EXPECT_NO_THROW(saved.check_spaces(env.observation_space(), env.action_space()));
  BoxSpace wrong = env.observation_space();
  wrong.low.push_back(0.0f);
  wrong.high.push_back(1.0f);
  wrong.names.push_back("y");
  EXPECT_THROW(saved.check_spaces(wrong, env.action_space()), CheckpointError);

  // A damaged model file is refused with the file's name in the message.
  std::string bytes = read_bytes(path);
  write_bytes(path, bytes.substr(0, bytes.size() - 100));
  try {
    DeployedPolicy::load(path);
    FAIL() << "a truncated model must be refused";
  } catch (const CheckpointError& error) {
    EXPECT_NE(std::string(error.what()).find(path.string()), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace upkie_rl
