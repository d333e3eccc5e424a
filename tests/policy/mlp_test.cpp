#include "policy/mlp.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace upkie_rl {
namespace {

// A 2-3-1 network with hand-picked weights: the output is checked against a sum written out.
struct SmallNetwork {
  ActorCriticNetworks networks = actor_critic_networks(2, 1, {3}, {}, Activation::kTanh);
  std::vector<float> parameters;

  SmallNetwork() {
    parameters.resize(static_cast<std::size_t>(networks.size));
    for (std::size_t i = 0; i < parameters.size(); ++i) {
      parameters[i] = 0.1f * static_cast<float>(i) - 0.5f;
    }
  }
};

TEST(MlpTest, ActivationAfterEveryLayerButTheOutputLayer) {
  const ActorCriticNetworks networks = actor_critic_networks(4, 2, {8, 6}, {5}, Activation::kELU);
  ASSERT_EQ(networks.actor.layers().size(), 3u);
  EXPECT_TRUE(networks.actor.activated(0));
  EXPECT_TRUE(networks.actor.activated(1));
  EXPECT_FALSE(networks.actor.activated(2));
  EXPECT_EQ(networks.actor.activation(), Activation::kELU);
  EXPECT_EQ(networks.actor.input_size(), 4);
  EXPECT_EQ(networks.actor.output_size(), 2);
  EXPECT_EQ(networks.critic.output_size(), 1);
  EXPECT_EQ(networks.actor.scratch_size(), 16u);  // Two buffers of the widest hidden layer.
  const ActorCriticLayout layout = actor_critic_layout(4, 2, {8, 6}, {5});
  EXPECT_EQ(networks.size, layout.size);
  EXPECT_EQ(networks.log_std, layout.log_std);
  EXPECT_EQ(networks.critic.layers()[0].weight, layout.critic[0].weight);
}

TEST(MlpTest, ForwardIsTheLayersWrittenOut) {
  SmallNetwork small;
  const Mlp& actor = small.networks.actor;
  const std::vector<float> input{0.7f, -1.3f};
  std::vector<float> scratch(actor.scratch_size());
  std::vector<float> output(1);
  actor.forward(small.parameters, input, scratch, output);

  const std::vector<float>& p = small.parameters;
  const DenseLayerLayout& hidden = actor.layers()[0];
  const DenseLayerLayout& head = actor.layers()[1];
  double expected = p[static_cast<std::size_t>(head.bias)];
  for (std::int64_t i = 0; i < 3; ++i) {
    double sum = p[static_cast<std::size_t>(hidden.bias + i)];
    for (std::int64_t j = 0; j < 2; ++j) {
      sum += static_cast<double>(p[static_cast<std::size_t>(hidden.weight + i * 2 + j)]) * input[j];
    }
    expected += static_cast<double>(p[static_cast<std::size_t>(head.weight + i)]) *
                static_cast<float>(std::tanh(sum));
  }
  EXPECT_NEAR(output[0], expected, 1e-6);
}

TEST(MlpTest, RefusesSpansOfTheWrongSize) {
  SmallNetwork small;
  const Mlp& actor = small.networks.actor;
  std::vector<float> scratch(actor.scratch_size());
  std::vector<float> output(1);
  const std::vector<float> short_input{0.7f};
  EXPECT_THROW(actor.forward(small.parameters, short_input, scratch, output),
               std::invalid_argument);
  const std::vector<float> input{0.7f, -1.3f};
  const std::vector<float> few_parameters(3);
  EXPECT_THROW(actor.forward(few_parameters, input, scratch, output), std::invalid_argument);
  std::vector<float> no_scratch;
  EXPECT_THROW(actor.forward(small.parameters, input, no_scratch, output), std::invalid_argument);
  std::vector<float> wide_output(2);
  EXPECT_THROW(actor.forward(small.parameters, input, scratch, wide_output), std::invalid_argument);
}

TEST(MlpTest, RefusesNoLayers) { EXPECT_THROW(Mlp({}, Activation::kReLU), std::invalid_argument); }

}  // namespace
}  // namespace upkie_rl
