// Fault injection (issue 26, item 2): crafted checkpoints whose CRC is valid are refused by
// the one gate, with the same message from every reader, and never crash it.

#include "policy/checkpoint_gate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>

#include "common/temp_files.hpp"
#include "policy/crc32c.hpp"
#include "policy/deployed_policy.hpp"
#include "policy/model_header.hpp"
#include "policy/parameter_layout.hpp"

namespace upkie_rl {
namespace {

const std::filesystem::path kModel =
    std::filesystem::path(UPKIE_RL_SOURCE_DIR) / "tests/data/policies/pendulum_bullet_seed0.ckpt";

std::filesystem::path temp_path(const std::string& name) {
  return testing::temp_path(name, "upkie_rl_checkpoint_gate");
}

/// The stored model with `change` applied, written with a valid CRC.
std::filesystem::path crafted(const std::string& name,
                              const std::function<void(CheckpointFile&)>& change) {
  CheckpointFile file = read_checkpoint_file(kModel);
  change(file);
  const std::filesystem::path path = temp_path(name + ".ckpt");
  write_checkpoint_file(file, path);
  return path;
}

/// A file of `header_text` and no tensors, with a valid CRC (no JSON library involved).
std::filesystem::path raw_checkpoint(const std::string& name, const std::string& header_text) {
  std::string bytes = "UPKIERL1";
  const std::uint64_t size = header_text.size();
  bytes.append(reinterpret_cast<const char*>(&size), sizeof(size));
  bytes += header_text;
  const std::uint32_t crc = crc32c(bytes);
  bytes.append(reinterpret_cast<const char*>(&crc), sizeof(crc));
  const std::filesystem::path path = temp_path(name + ".ckpt");
  testing::write_bytes(path, bytes);
  return path;
}

/// Both readers refuse `path` with the same message, which mentions `expected`.
void expect_refused(const std::filesystem::path& path, const std::string& expected) {
  std::string gate_message;
  try {
    read_checked_checkpoint(path);
    ADD_FAILURE() << path << " passed the gate";
  } catch (const CheckpointError& error) {
    gate_message = error.what();
  }
  EXPECT_NE(gate_message.find(expected), std::string::npos) << gate_message;
  EXPECT_NE(gate_message.find(path.string()), std::string::npos) << gate_message;
  try {
    DeployedPolicy::load(path);
    ADD_FAILURE() << path << " loaded as a policy";
  } catch (const CheckpointError& error) {
    EXPECT_EQ(std::string(error.what()), gate_message);
  }
}

TEST(CheckpointGate, TheStoredModelPasses) {
  EXPECT_NO_THROW(read_checked_checkpoint(kModel));
  EXPECT_NO_THROW(DeployedPolicy::load(kModel));
}

TEST(CheckpointGate, UnknownOptionalHeaderKeysAreTolerated) {
  const auto path = crafted("provenance", [](CheckpointFile& file) {
    file.header["provenance"] = {{"tool", "stable-baselines3"}, {"version", "2.3.0"}};
  });
  EXPECT_NO_THROW(read_checked_checkpoint(path));
}

TEST(CheckpointGate, DeeplyNestedHeaderIsRefusedWithoutRecursion) {
  const std::string nested = std::string(200'000, '[') + std::string(200'000, ']');
  expect_refused(raw_checkpoint("nested", "{\"format\": " + nested + "}"), "nested");
}

TEST(CheckpointGate, HeaderThatIsNotAnObjectIsRefused) {
  expect_refused(raw_checkpoint("array", "[1, 2, 3]"), "not a JSON object");
}

TEST(CheckpointGate, OtherVersionIsRefused) {
  expect_refused(crafted("version2", [](CheckpointFile& file) { file.header["version"] = 2; }),
                 "version 2");
}

TEST(CheckpointGate, OtherFormatIsRefused) {
  expect_refused(
      crafted("format", [](CheckpointFile& file) { file.header["format"] = "something else"; }),
      "not an upkie-rl checkpoint");
}

TEST(CheckpointGate, NanOrInfiniteWeightsAreRefused) {
  expect_refused(crafted("nan_weight",
                         [](CheckpointFile& file) {
                           file.tensors["policy.parameters"].values[7] =
                               std::numeric_limits<float>::quiet_NaN();
                         }),
                 "tensor 'policy.parameters' value 7");
  expect_refused(crafted("inf_moment",
                         [](CheckpointFile& file) {
                           auto& moment = file.tensors["optimizer.exp_avg_sq"].values;
                           if (moment.empty()) moment.resize(1);
                           moment[0] = std::numeric_limits<float>::infinity();
                         }),
                 "tensor 'optimizer.exp_avg_sq'");
}

/// Sets the stored model's optimiser moments: every m and v zero except value 3, (m, v).
void set_moments(CheckpointFile& file, float first, float second) {
  const FloatTensor& parameters = file.tensor("policy.parameters");
  for (const char* name : {"optimizer.exp_avg", "optimizer.exp_avg_sq"}) {
    file.tensors[name] = {parameters.shape, std::vector<float>(parameters.values.size(), 0.0f)};
  }
  file.tensors["optimizer.exp_avg"].values[3] = first;
  file.tensors["optimizer.exp_avg_sq"].values[3] = second;
}

// A negative second moment makes the first update after resume NaN (its square root), and a
// large first moment over a small second one makes it arbitrarily large; both are finite.
TEST(CheckpointGate, InconsistentAdamMomentsAreRefused) {
  expect_refused(crafted("negative_second_moment",
                         [](CheckpointFile& file) { set_moments(file, 0.0f, -0.25f); }),
                 "tensor 'optimizer.exp_avg_sq' value 3 is -0.25: a second moment cannot be "
                 "negative");
  expect_refused(
      crafted("large_first_moment", [](CheckpointFile& file) { set_moments(file, 1.0f, 1e-4f); }),
      "tensor 'optimizer.exp_avg' value 3 is 1: Adam allows at most");
  // At the limit both pass: |m| = sqrt(64 v), and a tiny m whose v underflowed to zero.
  const float second = 1e-4f;
  const float first = static_cast<float>(std::sqrt(kMaxAdamMomentRatio * second));
  EXPECT_NO_THROW(read_checked_checkpoint(crafted(
      "moments_at_limit", [&](CheckpointFile& file) { set_moments(file, -first, second); })));
  EXPECT_NO_THROW(read_checked_checkpoint(crafted(
      "underflowed_second_moment", [](CheckpointFile& file) { set_moments(file, 1e-7f, 0.0f); })));
}

/// Index in policy.parameters of weight `index` of layer `layer` of the stored model's
/// critic.
std::size_t critic_weight_index(std::size_t layer, std::int64_t index) {
  const CheckpointFile file = read_checkpoint_file(kModel);
  const PolicyShape shape = policy_shape_from_json(file.header.at("policy"));
  const ActorCriticLayout layout =
      actor_critic_layout(shape.observation_size, shape.action_size, shape.actor_hidden_sizes,
                          shape.critic_hidden_sizes);
  return static_cast<std::size_t>(layout.critic.at(layer).weight + index);
}

// Finite weights of 1e31 to 5e36 passed the gate and the deployed policy's action was NaN
// (found by the long clang run of checkpoint_fuzzer after 552,032 inputs; that input is
// fuzz/checkpoint_corpus/huge_weights). The gate now proves both networks finite for every
// input in range, and names the layer and its largest weight.
TEST(CheckpointGate, FiniteWeightsThatCanOverflowAreRefusedNamingTheWeight) {
  expect_refused(
      crafted("huge_actor_weight",
              [](CheckpointFile& file) { file.tensors["policy.parameters"].values[5] = 1e36f; }),
      "actor layer 0 can reach 1e+37 (limit 1e+30): tensor 'policy.parameters' "
      "value 5 is 1e+36");
  const std::size_t critic_output = critic_weight_index(2, 3);
  const auto huge_critic = crafted("huge_critic_weight", [critic_output](CheckpointFile& file) {
    file.tensors["policy.parameters"].values[critic_output] = 3e38f;
  });
  expect_refused(huge_critic, "critic layer 2 can reach");
  expect_refused(huge_critic,
                 "tensor 'policy.parameters' value " + std::to_string(critic_output) + " is 3e+38");
}

TEST(CheckpointGate, LogStdOutsideItsRangeIsRefused) {
  // The pendulum's one log σ is the last parameter (9090).
  expect_refused(crafted("log_std",
                         [](CheckpointFile& file) {
                           file.tensors["policy.parameters"].values.back() = 25.0f;
                         }),
                 "log std 0 (tensor 'policy.parameters' value 9090) is 25, outside [-20, 20]");
}

TEST(CheckpointGate, HugeCountersAreRefused) {
  expect_refused(crafted("counters",
                         [](CheckpointFile& file) {
                           file.header["counters"]["num_timesteps"] =
                               std::numeric_limits<std::int64_t>::max();
                         }),
                 "counters.num_timesteps");
  expect_refused(
      crafted("checkpoints_saved",
              [](CheckpointFile& file) { file.header["run"]["checkpoints_saved"] = -3; }),
      "run.checkpoints_saved");
}

TEST(CheckpointGate, NormalisationSettingsOutOfRangeAreRefused) {
  expect_refused(crafted("epsilon",
                         [](CheckpointFile& file) {
                           file.header["normalization"]["config"]["epsilon"] = 1e39;
                         }),
                 "epsilon");
  expect_refused(crafted("variance",
                         [](CheckpointFile& file) {
                           file.header["normalization"]["observations"]["var"][0] = -1.0;
                         }),
                 "var");
}

TEST(CheckpointGate, ShapesInconsistentWithTheSpacesOrNetworkAreRefused) {
  expect_refused(
      crafted("shape",
              [](CheckpointFile& file) { file.header["policy"]["observation_size"] = 99; }),
      "do not match the stored spaces");
  expect_refused(crafted("huge_layer",
                         [](CheckpointFile& file) {
                           file.header["policy"]["actor_hidden_sizes"] = {60000, 60000};
                         }),
                 "exceed the limit");
  expect_refused(crafted("short_tensor",
                         [](CheckpointFile& file) {
                           file.tensors["policy.parameters"].values.pop_back();
                           file.tensors["policy.parameters"].shape = {static_cast<std::int64_t>(
                               file.tensors["policy.parameters"].values.size())};
                         }),
                 "policy.parameters");
  expect_refused(
      crafted("action_bounds",
              [](CheckpointFile& file) { file.header["action_space"]["high"][0] = "inf"; }),
      "action space component 0");
}

TEST(CheckpointGate, DevicesAndDirectoriesAreRefusedWithoutReading) {
  expect_refused("/dev/zero", "not a regular file");
  expect_refused(std::filesystem::temp_directory_path(), "is a directory");
}

}  // namespace
}  // namespace upkie_rl
