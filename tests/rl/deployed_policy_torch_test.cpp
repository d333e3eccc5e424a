// The torch-free DeployedPolicy against the trainer's torch ActorCritic: same actions from
// the file the trainer writes.

#include <gtest/gtest.h>

#include <stdexcept>

#include "common/normalization_state.hpp"
#include "common/temp_files.hpp"
#include "policy/deployed_policy.hpp"
#include "rl/runs/ppo_checkpoint.hpp"

namespace upkie_rl {
namespace {

/// A vector env that only has spaces: enough to build a Ppo and write its checkpoint.
class SpacesOnlyVectorEnv final : public VectorEnv {
 public:
  SpacesOnlyVectorEnv(BoxSpace observation_space, BoxSpace action_space)
      : observation_space_(std::move(observation_space)), action_space_(std::move(action_space)) {}

  std::size_t num_envs() const override { return 1; }
  const BoxSpace& observation_space() const override { return observation_space_; }
  const BoxSpace& action_space() const override { return action_space_; }
  std::span<const float> reset(std::optional<std::uint64_t>) override {
    throw std::logic_error("not steppable");
  }
  const VectorStep& step(std::span<const float>) override {
    throw std::logic_error("not steppable");
  }

 private:
  BoxSpace observation_space_;
  BoxSpace action_space_;
};

TEST(DeployedPolicyVsTorch, SameActionsAsTheActorCriticForEachActivation) {
  BoxSpace observation_space;
  for (int i = 0; i < 5; ++i) observation_space.add("o" + std::to_string(i), -INFINITY, INFINITY);
  BoxSpace action_space;
  action_space.add("a0", -0.5f, 0.5f);
  action_space.add("a1", -1.0f, 2.0f);
  action_space.add("a2", -20.0f, 20.0f);  // wide: the mean is rarely clipped
  const std::vector<double> mean{0.1, -0.2, 0.3, 0.0, 1.0};
  const std::vector<double> var{4.0, 0.25, 1.0, 9.0, 0.5};
  const double clip = 3.0;
  const nlohmann::json normalization = testing::normalization_state(mean, var, clip);

  for (const Activation activation : all_activations()) {
    SCOPED_TRACE(activation_name(activation));
    SpacesOnlyVectorEnv env(observation_space, action_space);
    TrainingConfig config;
    config.env_id = "spaces-only";
    config.num_envs = 1;
    config.policy.actor_hidden_sizes = {16, 8};
    config.policy.critic_hidden_sizes = {12};
    config.policy.activation = activation;
    config.ppo.n_steps = 64;
    config.ppo.batch_size = 16;
    Ppo ppo(env, config);
    // Random weights everywhere (the initial action head is nearly zero).
    torch::manual_seed(3);
    {
      torch::NoGradGuard no_grad;
      ppo.policy().flat_parameters().copy_(torch::randn({ppo.policy().flat_parameters().numel()}) *
                                           0.7);
    }
    const auto path = testing::temp_path(std::string(activation_name(activation)) + ".ckpt",
                                         "upkie_rl_deployed_policy_torch");
    save_checkpoint(make_ppo_checkpoint(ppo, normalization), path);
    DeployedPolicy policy = DeployedPolicy::load(path);
    EXPECT_EQ(policy.env_id(), "spaces-only");

    const std::int64_t rows = 200;
    const torch::Tensor observations = torch::rand({rows, 5}) * 8.0 - 4.0;
    std::vector<float> actions(static_cast<std::size_t>(rows) * 3);
    policy.act_batch({observations.data_ptr<float>(), static_cast<std::size_t>(rows * 5)}, actions);

    // The same computation with torch: normalise, actor mean, clip to the bounds.
    torch::NoGradGuard no_grad;
    const auto as_tensor = [](const std::vector<double>& values) {
      return torch::tensor(values, torch::kFloat64);
    };
    const torch::Tensor normalized =
        ((observations.to(torch::kFloat64) - as_tensor(mean)) / (as_tensor(var) + 1e-8).sqrt())
            .clamp(-clip, clip)
            .to(torch::kFloat32);
    const torch::Tensor expected =
        torch::max(torch::min(ppo.policy().action_mean(normalized),
                              torch::tensor(action_space.high, torch::kFloat32)),
                   torch::tensor(action_space.low, torch::kFloat32))
            .contiguous();
    const float* reference = expected.data_ptr<float>();
    int clipped = 0;
    for (std::size_t k = 0; k < actions.size(); ++k) {
      EXPECT_NEAR(actions[k], reference[k], 1e-5) << "value " << k;
      clipped += reference[k] == 0.5f || reference[k] == -0.5f;
    }
    EXPECT_GT(clipped, 0);  // The clipping to the action bounds was exercised.
    const float max_action = expected.abs().max().item<float>();
    EXPECT_GT(max_action, 1.0f);  // Not a policy whose outputs all vanish.
  }
}

}  // namespace
}  // namespace upkie_rl
