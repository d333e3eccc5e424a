#include "policy/model_header.hpp"

#include <gtest/gtest.h>

#include "policy/checkpoint_file.hpp"

namespace upkie_rl {
namespace {

TEST(ModelHeader, PolicyShapeRoundTripAndBounds) {
  const PolicyShape shape{4, 1, {64, 32}, {16}, Activation::kTanh};
  const nlohmann::json json = policy_shape_to_json(shape);
  EXPECT_EQ(json.at("activation"), "tanh");
  const PolicyShape read = policy_shape_from_json(json);
  EXPECT_EQ(read.observation_size, 4);
  EXPECT_EQ(read.action_size, 1);
  EXPECT_EQ(read.actor_hidden_sizes, shape.actor_hidden_sizes);
  EXPECT_EQ(read.critic_hidden_sizes, shape.critic_hidden_sizes);
  EXPECT_EQ(read.activation, Activation::kTanh);
  nlohmann::json huge = json;
  huge["critic_hidden_sizes"] = {2'000'000};
  EXPECT_THROW(policy_shape_from_json(huge), CheckpointError);
  nlohmann::json unknown = json;
  unknown["activation"] = "swish";
  EXPECT_THROW(policy_shape_from_json(unknown), std::invalid_argument);
}

TEST(ModelHeader, EnvIdFromTheConfiguration) {
  const nlohmann::json header = {{"config", "seed: 3\nenv:\n  id: Upkie-Bullet-Servos\n"}};
  EXPECT_EQ(checkpoint_env_id(header), "Upkie-Bullet-Servos");
  EXPECT_THROW(checkpoint_env_id(nlohmann::json::object()), CheckpointError);
  EXPECT_THROW(checkpoint_env_id({{"config", 3}}), CheckpointError);
  EXPECT_THROW(checkpoint_env_id({{"config", "env: {}\n"}}), CheckpointError);
}

}  // namespace
}  // namespace upkie_rl
