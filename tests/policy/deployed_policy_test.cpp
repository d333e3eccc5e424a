#include "policy/deployed_policy.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "common/allocation_counter.hpp"
#include "common/normalization_state.hpp"
#include "common/temp_files.hpp"
#include "policy/parameter_layout.hpp"
#include "policy/policy_output_error.hpp"
#include "policy/space_json.hpp"

namespace upkie_rl {
namespace {

std::filesystem::path temp_path(const std::string& name) {
  return testing::temp_path(name, "upkie_rl_deployed_policy");
}

BoxSpace make_space(std::size_t size, float bound, const std::string& prefix) {
  BoxSpace space;
  for (std::size_t i = 0; i < size; ++i) space.add(prefix + std::to_string(i), -bound, bound);
  return space;
}

/// A model file as the trainer writes one (format, config, spaces, policy shape,
/// normalisation, parameters), with random weights.
struct ModelFixture {
  BoxSpace observation_space = make_space(3, 10.0f, "o");
  BoxSpace action_space = make_space(2, 0.5f, "a");
  std::vector<std::int64_t> actor_hidden{5, 4};
  std::vector<std::int64_t> critic_hidden{6};
  std::string activation = "tanh";
  std::vector<double> mean{0.1, -0.2, 0.3};
  std::vector<double> var{4.0, 0.25, 1.0};
  std::vector<float> parameters;

  CheckpointFile file() {
    const std::int64_t count = actor_critic_layout(3, 2, actor_hidden, critic_hidden).size;
    std::mt19937 generator(42);
    std::normal_distribution<float> normal(0.0f, 0.8f);
    parameters.resize(static_cast<std::size_t>(count));
    for (float& p : parameters) p = normal(generator);
    CheckpointFile file;
    file.header = {{"format", "upkie-rl checkpoint"},
                   {"version", 1},
                   {"config", "env:\n  id: Upkie-Bullet-Pendulum\n  num_envs: 10\n"},
                   {"policy",
                    {{"observation_size", 3},
                     {"action_size", 2},
                     {"actor_hidden_sizes", actor_hidden},
                     {"critic_hidden_sizes", critic_hidden},
                     {"activation", activation}}},
                   {"observation_space", space_to_json(observation_space)},
                   {"action_space", space_to_json(action_space)},
                   {"normalization", testing::normalization_state(mean, var, 2.0)}};
    file.tensors["policy.parameters"] = {{count}, parameters};
    return file;
  }

  /// The hidden layers' activation, written independently of policy/activation.hpp.
  double hidden_activation(double x) const {
    if (activation == "tanh") return std::tanh(x);
    if (activation == "elu") return x > 0.0 ? x : std::expm1(x);
    return std::max(x, 0.0);
  }

  /// The policy's action computed independently, in double precision.
  std::vector<double> reference(const std::vector<float>& observation) const {
    std::vector<double> x(3);
    for (std::size_t i = 0; i < 3; ++i) {
      x[i] = std::clamp((observation[i] - mean[i]) / std::sqrt(var[i] + 1e-8), -2.0, 2.0);
    }
    std::size_t offset = 0;
    std::vector<std::int64_t> sizes = actor_hidden;
    sizes.push_back(2);
    for (std::size_t l = 0; l < sizes.size(); ++l) {
      const auto out = static_cast<std::size_t>(sizes[l]);
      const std::size_t in = x.size();
      std::vector<double> y(out);
      for (std::size_t i = 0; i < out; ++i) {
        double sum = parameters[offset + out * in + i];
        for (std::size_t j = 0; j < in; ++j) sum += parameters[offset + i * in + j] * x[j];
        y[i] = l + 1 < sizes.size() ? hidden_activation(sum) : std::clamp(sum, -0.5, 0.5);
      }
      offset += out * in + out;
      x = y;
    }
    return x;
  }
};

TEST(DeployedPolicy, ActsLikeAnIndependentReference) {
  for (const std::string activation : {"tanh", "relu", "elu"}) {
    SCOPED_TRACE(activation);
    ModelFixture model;
    model.activation = activation;
    const auto path = temp_path(activation + ".ckpt");
    write_checkpoint_file(model.file(), path);
    DeployedPolicy policy = DeployedPolicy::load(path);
    EXPECT_EQ(policy.env_id(), "Upkie-Bullet-Pendulum");
    EXPECT_EQ(policy.observation_space().names, model.observation_space.names);
    EXPECT_EQ(policy.shape().actor_hidden_sizes, model.actor_hidden);
    std::mt19937 generator(1);
    std::uniform_real_distribution<float> uniform(-3.0f, 3.0f);
    int clipped = 0;
    for (int trial = 0; trial < 200; ++trial) {
      const std::vector<float> observation{uniform(generator), uniform(generator),
                                           uniform(generator)};
      std::vector<float> action(2);
      policy.act(observation, action);
      const std::vector<double> expected = model.reference(observation);
      for (std::size_t j = 0; j < 2; ++j) {
        EXPECT_NEAR(action[j], expected[j], 1e-5);
        clipped += std::abs(expected[j]) == 0.5;
      }
    }
    EXPECT_GT(clipped, 0);  // the clipping to the action bounds was exercised
  }
}

TEST(DeployedPolicy, BatchesRowsAndChecksSizes) {
  ModelFixture model;
  const auto path = temp_path("batch.ckpt");
  write_checkpoint_file(model.file(), path);
  DeployedPolicy policy = DeployedPolicy::load(path);
  const std::vector<float> observations{0.1f, 0.2f, 0.3f, -1.0f, 2.0f, 0.5f};
  std::vector<float> actions(4);
  policy.act_batch(observations, actions);
  std::vector<float> single(2);
  policy.act(std::span<const float>(observations).subspan(3, 3), single);
  EXPECT_EQ(actions[2], single[0]);
  EXPECT_EQ(actions[3], single[1]);
  std::vector<float> wrong(3);
  EXPECT_THROW(policy.act(observations, single), std::invalid_argument);
  EXPECT_THROW(policy.act(std::span<const float>(observations).first(3), wrong),
               std::invalid_argument);
  EXPECT_THROW(policy.act_batch(observations, wrong), std::invalid_argument);
  EXPECT_NO_THROW(policy.check_spaces(model.observation_space, model.action_space));
  EXPECT_THROW(policy.check_spaces(make_space(3, 9.0f, "o"), model.action_space), CheckpointError);
}

TEST(DeployedPolicy, ActAllocatesNothing) {
  ModelFixture model;
  const auto path = temp_path("allocation.ckpt");
  write_checkpoint_file(model.file(), path);
  DeployedPolicy policy = DeployedPolicy::load(path);
  const std::vector<float> observation{0.1f, 0.2f, 0.3f};
  std::vector<float> action(2);
  policy.act(observation, action);
  const std::size_t before = testing::this_thread_allocations;
  for (int i = 0; i < 100; ++i) policy.act(observation, action);
  EXPECT_EQ(testing::this_thread_allocations, before);
}

TEST(DeployedPolicy, NonFiniteObservationsAreRefusedNamingTheComponent) {
  ModelFixture model;
  DeployedPolicy policy = DeployedPolicy::from_checkpoint(model.file(), "fixture");
  std::vector<float> action(2);
  try {
    policy.act(std::vector<float>{0.1f, std::nanf(""), 0.3f}, action);
    ADD_FAILURE() << "a NaN observation was acted on";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("observation component 1 (o1) is nan"),
              std::string::npos)
        << error.what();
  }
}

// Without normalisation, an unbounded observation component is checked up to
// kMaxCheckedObservation: beyond it, weights the gate accepts can overflow, and act()
// refuses the NaN instead of passing it on (clamping does not remove a NaN).
TEST(DeployedPolicy, AnOverflowBeyondTheCheckedRangeIsRefusedNotPassedOn) {
  ModelFixture model;
  model.activation = "relu";
  const float infinity = std::numeric_limits<float>::infinity();
  model.observation_space = BoxSpace();
  for (const char* name : {"o0", "o1", "o2"})
    model.observation_space.add(name, -infinity, infinity);
  CheckpointFile file = model.file();
  file.header["normalization"] = nullptr;
  std::vector<float>& parameters = file.tensors["policy.parameters"].values;
  const ActorCriticLayout layout =
      actor_critic_layout(3, 2, model.actor_hidden, model.critic_hidden);
  const auto fill = [&parameters](const DenseLayerLayout& layer, auto value_of) {
    for (std::int64_t i = 0; i < layer.out * layer.in; ++i)
      parameters[layer.weight + i] = value_of(i);
    for (std::int64_t i = 0; i < layer.out; ++i) parameters[layer.bias + i] = 0.0f;
  };
  // The bound for inputs within 1e6: about 7e25 (the gate accepts); an input of 1e30
  // overflows the first layer to +inf, and the output layer adds +inf and -inf.
  fill(layout.actor[0], [](std::int64_t) { return 1e18f; });
  fill(layout.actor[1], [](std::int64_t) { return 1.0f; });
  fill(layout.actor[2], [](std::int64_t i) { return i % 2 == 0 ? 1.0f : -1.0f; });
  DeployedPolicy policy = DeployedPolicy::from_checkpoint(file, "crafted");
  std::vector<float> action(2);
  EXPECT_NO_THROW(policy.act(std::vector<float>{0.0f, 1e6f, 0.0f}, action));
  EXPECT_TRUE(std::isfinite(action[0]) && std::isfinite(action[1]));
  try {
    policy.act(std::vector<float>{0.0f, 1e30f, 0.0f}, action);
    ADD_FAILURE() << "a NaN action was passed on: " << action[0];
  } catch (const PolicyOutputError& error) {
    EXPECT_EQ(std::string(error.what()).rfind("policy action component 0 (a0) is nan", 0), 0u)
        << error.what();
  }
}

TEST(DeployedPolicy, ForeignOrInconsistentModelsNameTheProblem) {
  auto expect_error = [](CheckpointFile file, const std::string& text) {
    const auto path = temp_path("bad_model.ckpt");
    write_checkpoint_file(file, path);
    try {
      DeployedPolicy::load(path);
      FAIL() << "expected an error containing '" << text << "'";
    } catch (const CheckpointError& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find(text), std::string::npos) << message;
      EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    }
  };
  ModelFixture model;
  CheckpointFile file = model.file();
  file.header["format"] = "something else";
  expect_error(file, "not an upkie-rl checkpoint");
  file = model.file();
  file.header.erase("config");
  expect_error(file, "no configuration");
  file = model.file();
  file.header["config"] = "env: [1, 2]\n";
  expect_error(file, "env.id");
  file = model.file();
  file.header["policy"]["action_size"] = 3;
  expect_error(file, "policy sizes do not match the stored spaces");
  file = model.file();
  file.header["policy"]["actor_hidden_sizes"] = {5, 0};
  expect_error(file, "policy.actor_hidden_sizes: 0 is outside [1, 65536]");
  file = model.file();
  file.header["policy"]["activation"] = "swish";
  expect_error(file, "unknown activation 'swish'");
  file = model.file();
  file.tensors["policy.parameters"].values.pop_back();
  file.tensors["policy.parameters"].shape = {file.tensors["policy.parameters"].shape[0] - 1};
  expect_error(file, "policy.parameters");
  file = model.file();
  file.header["normalization"]["observations"]["mean"] = {0.0};
  expect_error(file, "normalization.observations");
  file = model.file();
  file.header.erase("action_space");
  expect_error(file, "malformed header");
}

}  // namespace
}  // namespace upkie_rl
