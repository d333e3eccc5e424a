#include "policy/network_output_bound.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "policy/checkpoint_gate.hpp"
#include "policy/mlp.hpp"
#include "policy/model_header.hpp"
#include "policy/space_json.hpp"

namespace upkie_rl {
namespace {

// The bound holds: random networks of every activation, with inputs drawn inside the
// bounds and at their corners, never give an output above it.
TEST(NetworkOutputBound, BoundsTheOutputOfRandomNetworksOfEveryActivation) {
  std::mt19937 generator(7);
  std::normal_distribution<float> weight(0.0f, 2.0f);
  const std::vector<double> input_bounds{3.0, 0.5, 10.0};
  for (Activation activation : all_activations()) {
    const ActorCriticNetworks networks = actor_critic_networks(3, 2, {6, 5}, {4}, activation);
    std::vector<float> parameters(static_cast<std::size_t>(networks.size));
    for (float& value : parameters) value = weight(generator);
    const double bound =
        check_network_bound(parameters, networks.actor.layers(), input_bounds, "actor");
    std::vector<float> scratch(networks.actor.scratch_size());
    std::vector<float> output(2);
    double largest = 0.0;
    for (int trial = 0; trial < 2000; ++trial) {
      std::vector<float> input(3);
      for (std::size_t i = 0; i < input.size(); ++i) {
        const double span = input_bounds[i];
        input[i] = static_cast<float>(
            trial % 2 == 0 ? (generator() % 2 ? span : -span)
                           : std::uniform_real_distribution<double>(-span, span)(generator));
      }
      networks.actor.forward(parameters, input, scratch, output);
      for (float value : output) largest = std::max(largest, std::abs(double{value}));
    }
    EXPECT_LE(largest, bound) << activation_name(activation);
    EXPECT_GT(largest, 0.0) << activation_name(activation);
  }
}

TEST(NetworkOutputBound, RawObservationsAreBoundedByTheirSpaceUpToTheCheckedMagnitude) {
  BoxSpace space;
  space.add("angle", -3.0f, 2.0f);
  space.add("position", -std::numeric_limits<float>::infinity(),
            std::numeric_limits<float>::infinity());
  space.add("huge", -3e38f, 3e38f);
  const ObservationNormalizer identity(3);
  EXPECT_EQ(network_input_bounds(space, identity),
            (std::vector<double>{3.0, kMaxCheckedObservation, kMaxCheckedObservation}));
}

TEST(NetworkOutputBound, ABoundBeyondTheLimitNamesTheLayerAndItsLargestWeight) {
  const ActorCriticNetworks networks = actor_critic_networks(2, 1, {3}, {}, Activation::kReLU);
  std::vector<float> parameters(static_cast<std::size_t>(networks.size), 1.0f);
  parameters[networks.actor.layers()[1].weight + 2] = -3e29f;  // output layer, third weight
  try {
    check_network_bound(parameters, networks.actor.layers(), {1.0, 1.0}, "actor");
    ADD_FAILURE() << "a bound of 1.5e30 passed";
  } catch (const CheckpointError& error) {
    EXPECT_EQ(std::string(error.what()).find("actor layer 1 can reach"), 0u) << error.what();
    EXPECT_NE(std::string(error.what())
                  .find("tensor 'policy.parameters' value " +
                        std::to_string(networks.actor.layers()[1].weight + 2) + " is -3e+29"),
              std::string::npos)
        << error.what();
  }
}

// The checked-in trained policies load, and their actors stay far below the limit.
TEST(NetworkOutputBound, TheStoredPoliciesStayFarBelowTheLimit) {
  for (const char* name :
       {"pendulum_bullet_seed0", "pendulum_mujoco_seed0", "pendulum_robust_mujoco_seed4",
        "servos_balance_mujoco_seed0", "velocity_mujoco_seed0", "velocity_reality_mujoco_seed0"}) {
    const CheckpointFile file = read_checked_checkpoint(std::string(UPKIE_RL_TEST_DATA_DIR) +
                                                        "/policies/" + name + ".ckpt");
    const PolicyShape shape = policy_shape_from_json(file.header.at("policy"));
    const ActorCriticLayout layout =
        actor_critic_layout(shape.observation_size, shape.action_size, shape.actor_hidden_sizes,
                            shape.critic_hidden_sizes);
    const BoxSpace observation_space = space_from_json(file.header.at("observation_space"));
    const ObservationNormalizer normalizer = ObservationNormalizer::from_state(
        file.header.at("normalization"), observation_space.size());
    const std::vector<double> inputs = network_input_bounds(observation_space, normalizer);
    const std::vector<float>& parameters = file.tensor("policy.parameters").values;
    const double actor = check_network_bound(parameters, layout.actor, inputs, "actor");
    const double critic = check_network_bound(parameters, layout.critic, inputs, "critic");
    std::cout << name << ": actor bound " << actor << ", critic bound " << critic << "\n";
    EXPECT_LT(actor, 1e4) << name;
    EXPECT_LT(critic, 1e4) << name;
  }
}

}  // namespace
}  // namespace upkie_rl
