#include "rl/saved_policy.hpp"

#include <algorithm>

#include "rl/checkpoint.hpp"
#include "rl/ppo_checkpoint.hpp"
#include "rl/training_config.hpp"

namespace upkie_rl {

SavedPolicy SavedPolicy::load(const std::filesystem::path& path) {
  const Checkpoint checkpoint = load_checkpoint(path);
  const std::string where = "model " + path.string() + ": ";
  SavedPolicy saved;
  try {
    const nlohmann::json& header = checkpoint.header;
    if (header.value("format", "") != "upkie-rl checkpoint") {
      throw CheckpointError("not an upkie-rl model");
    }
    const TrainingConfig config = parse_training_config(checkpoint_config_yaml(checkpoint));
    saved.env_id_ = config.env_id;
    saved.observation_space_ = space_from_json(header.at("observation_space"));
    saved.action_space_ = space_from_json(header.at("action_space"));
    const nlohmann::json& shape = header.at("policy");
    PolicyConfig policy_config;
    policy_config.actor_hidden_sizes =
        shape.at("actor_hidden_sizes").get<std::vector<std::int64_t>>();
    policy_config.critic_hidden_sizes =
        shape.at("critic_hidden_sizes").get<std::vector<std::int64_t>>();
    policy_config.activation = parse_activation(shape.at("activation").get<std::string>());
    const auto observation_size = shape.at("observation_size").get<std::int64_t>();
    const auto action_size = shape.at("action_size").get<std::int64_t>();
    if (observation_size != static_cast<std::int64_t>(saved.observation_space_.size()) ||
        action_size != static_cast<std::int64_t>(saved.action_space_.size())) {
      throw CheckpointError("policy sizes do not match the stored spaces");
    }
    saved.policy_ = std::make_unique<ActorCritic>(observation_size, action_size, policy_config, 0);
    const torch::Tensor& parameters =
        checkpoint.tensor("policy.parameters", saved.policy_->flat_parameters().numel());
    {
      torch::NoGradGuard no_grad;
      saved.policy_->flat_parameters().copy_(parameters.view({-1}));
    }
    saved.normalizer_ = ObservationNormalizer::from_state(
        header.value("normalization", nlohmann::json()), saved.observation_space_.size());
  } catch (const CheckpointError& error) {
    throw CheckpointError(where + error.what());
  } catch (const std::invalid_argument& error) {
    throw CheckpointError(where + error.what());
  } catch (const nlohmann::json::exception& error) {
    throw CheckpointError(where + "malformed header: " + error.what());
  }
  saved.inference_ = std::make_unique<PolicyInference>(*saved.policy_, 1);
  saved.normalized_.resize(saved.observation_space_.size());
  return saved;
}

void SavedPolicy::check_spaces(const BoxSpace& observation_space,
                               const BoxSpace& action_space) const {
  check_same_space(observation_space_, observation_space, "observation space");
  check_same_space(action_space_, action_space, "action space");
}

void SavedPolicy::act(std::span<const float> observation, std::span<float> action) {
  if (observation.size() != normalized_.size() || action.size() != action_space_.size()) {
    throw std::invalid_argument("SavedPolicy::act: expected " + std::to_string(normalized_.size()) +
                                " observation and " + std::to_string(action_space_.size()) +
                                " action values");
  }
  normalizer_.normalize(observation, normalized_);
  inference_->run_actor(normalized_);
  const std::span<const float> mean = inference_->means();
  for (std::size_t j = 0; j < action.size(); ++j) {
    action[j] = std::clamp(mean[j], action_space_.low[j], action_space_.high[j]);
  }
}

}  // namespace upkie_rl
