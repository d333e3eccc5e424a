#include "policy/parameter_layout.hpp"

#include <gtest/gtest.h>

namespace upkie_rl {
namespace {

TEST(ParameterLayout, ActorThenCriticThenLogStd) {
  // actor 3→4→2, critic 3→5→1, log σ 2; offsets counted by hand.
  const ActorCriticLayout layout = actor_critic_layout(3, 2, {4}, {5});
  ASSERT_EQ(layout.actor.size(), 2u);
  ASSERT_EQ(layout.critic.size(), 2u);
  auto expect_layer = [](const DenseLayerLayout& layer, std::int64_t in, std::int64_t out,
                         std::int64_t weight, std::int64_t bias) {
    EXPECT_EQ(layer.in, in);
    EXPECT_EQ(layer.out, out);
    EXPECT_EQ(layer.weight, weight);
    EXPECT_EQ(layer.bias, bias);
  };
  expect_layer(layout.actor[0], 3, 4, 0, 12);
  expect_layer(layout.actor[1], 4, 2, 16, 24);
  expect_layer(layout.critic[0], 3, 5, 26, 41);
  expect_layer(layout.critic[1], 5, 1, 46, 51);
  EXPECT_EQ(layout.log_std, 52);
  EXPECT_EQ(layout.size, 54);
  // No hidden layer: the output layer reads the input.
  const ActorCriticLayout linear = actor_critic_layout(3, 2, {}, {});
  expect_layer(linear.actor[0], 3, 2, 0, 6);
  EXPECT_EQ(linear.size, (2 * 3 + 2) + (1 * 3 + 1) + 2);
}

}  // namespace
}  // namespace upkie_rl
