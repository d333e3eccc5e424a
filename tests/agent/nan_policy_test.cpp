// upkie-rl-agent with a policy whose weights are finite but overflow to a NaN output: the
// checkpoint gate proves the network's output finite for every observation in range
// (policy/network_output_bound.hpp), so it refuses this policy at load, before anything is
// sent, naming the weight; the runner sends the Stop request and exits with status 2.
// Earlier the gate let it through and the supervisor's check of the policy output stopped
// the run (that check stays, behind DeployedPolicy::act's own refusal of a non-finite
// action: tests/policy/deployed_policy_test.cpp, tests/agent/supervisor_test.cpp).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "agent/agent_spine.hpp"
#include "common/temp_files.hpp"
#include "policy/checkpoint_file.hpp"
#include "policy/checkpoint_gate.hpp"
#include "policy/deployed_policy.hpp"
#include "policy/model_header.hpp"
#include "policy/parameter_layout.hpp"

namespace upkie_rl {
namespace {

using testing::kPendulum;
using testing::Spine;
using testing::start_agent;
using testing::temp_path;

/// The pendulum policy made to output NaN with finite weights (the gate refuses non-finite
/// ones): normalisation means of -1000 put every normalised observation at the clip, +10;
/// first-layer weights of 1e38 overflow to +inf, which ReLU and all-positive second-layer
/// weights carry; output weights of alternating sign add +inf and -inf.
CheckpointFile nan_output_policy() {
  CheckpointFile file = read_checkpoint_file(kPendulum);
  nlohmann::json& mean = file.header["normalization"]["observations"]["mean"];
  for (auto& value : mean) value = -1000.0;
  const PolicyShape shape = policy_shape_from_json(file.header.at("policy"));
  const ActorCriticLayout layout =
      actor_critic_layout(shape.observation_size, shape.action_size, shape.actor_hidden_sizes,
                          shape.critic_hidden_sizes);
  std::vector<float>& parameters = file.tensors.at("policy.parameters").values;
  const auto fill = [&](const DenseLayerLayout& layer, auto value_of) {
    for (std::int64_t i = 0; i < layer.out * layer.in; ++i) {
      parameters[static_cast<std::size_t>(layer.weight + i)] = value_of(i);
    }
    for (std::int64_t i = 0; i < layer.out; ++i) {
      parameters[static_cast<std::size_t>(layer.bias + i)] = 0.0f;
    }
  };
  const std::vector<DenseLayerLayout>& actor = layout.actor;
  fill(actor.front(), [](std::int64_t) { return 1e38f; });
  for (std::size_t layer = 1; layer + 1 < actor.size(); ++layer) {
    fill(actor[layer], [](std::int64_t) { return 1.0f; });
  }
  fill(actor.back(), [](std::int64_t i) { return i % 2 == 0 ? 1.0f : -1.0f; });
  return file;
}

TEST(AgentRunnerNan, AFinitePolicyThatCanOutputNanIsRefusedBeforeAnythingStarts) {
  const CheckpointFile file = nan_output_policy();
  const auto crafted = temp_path("agent_nan_policy.ckpt");
  write_checkpoint_file(file, crafted);
  Spine spine("nan");
  auto agent = start_agent(spine, crafted.string(), "nan", {"--duration", "5"});
  EXPECT_EQ(agent->wait(), 2);
  const std::string output = agent->output();
  EXPECT_NE(
      output.find("idle -> stopping: checkpoint " + crafted.string() + ": actor layer 0 can reach"),
      std::string::npos)
      << output;
  EXPECT_NE(output.find("tensor 'policy.parameters' value 0 is 1e+38"), std::string::npos)
      << output;
  EXPECT_NE(output.find("Stop request sent to the spine"), std::string::npos) << output;
  EXPECT_EQ(output.find("-> running"), std::string::npos) << output;
}

TEST(AgentRunnerNan, TheGateRefusesTheCraftedPolicyEverywhere) {
  const auto crafted = temp_path("nan_output_policy.ckpt");
  write_checkpoint_file(nan_output_policy(), crafted);
  EXPECT_THROW(DeployedPolicy::load(crafted), CheckpointError);
  EXPECT_THROW(read_checked_checkpoint(crafted), CheckpointError);
}

}  // namespace
}  // namespace upkie_rl
