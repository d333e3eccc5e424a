#include "policy/model_header.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>

#include "policy/checkpoint_file.hpp"

namespace upkie_rl {

nlohmann::json policy_shape_to_json(const PolicyShape& shape) {
  return {{"observation_size", shape.observation_size},
          {"action_size", shape.action_size},
          {"actor_hidden_sizes", shape.actor_hidden_sizes},
          {"critic_hidden_sizes", shape.critic_hidden_sizes},
          {"activation", activation_name(shape.activation)}};
}

PolicyShape policy_shape_from_json(const nlohmann::json& json) {
  PolicyShape shape;
  shape.observation_size = json.at("observation_size").get<std::int64_t>();
  shape.action_size = json.at("action_size").get<std::int64_t>();
  shape.actor_hidden_sizes = json.at("actor_hidden_sizes").get<std::vector<std::int64_t>>();
  shape.critic_hidden_sizes = json.at("critic_hidden_sizes").get<std::vector<std::int64_t>>();
  shape.activation = parse_activation(json.at("activation").get<std::string>());
  // Bounded so that a damaged header cannot ask for an absurd allocation.
  auto valid = [](std::int64_t size) { return size > 0 && size <= 1'000'000; };
  if (!valid(shape.observation_size) || !valid(shape.action_size) ||
      !std::all_of(shape.actor_hidden_sizes.begin(), shape.actor_hidden_sizes.end(), valid) ||
      !std::all_of(shape.critic_hidden_sizes.begin(), shape.critic_hidden_sizes.end(), valid)) {
    throw CheckpointError("policy sizes must be in [1, 1000000]");
  }
  return shape;
}

std::string checkpoint_config_yaml(const nlohmann::json& header) {
  const auto found = header.find("config");
  if (found == header.end() || !found->is_string()) {
    throw CheckpointError("checkpoint has no configuration");
  }
  return found->get<std::string>();
}

std::string checkpoint_env_id(const nlohmann::json& header) {
  const std::string config = checkpoint_config_yaml(header);
  try {
    return YAML::Load(config)["env"]["id"].as<std::string>();
  } catch (const YAML::Exception& error) {
    throw CheckpointError(std::string("configuration has no env.id: ") + error.what());
  }
}

EnvOptions checkpoint_env_options(const nlohmann::json& header) {
  const std::string config = checkpoint_config_yaml(header);
  EnvOptions options;
  try {
    const YAML::Node node = YAML::Load(config)["env"]["options"];
    if (!node || node.IsNull()) return options;
    if (!node.IsMap()) throw CheckpointError("configuration's env.options is not a map");
    for (const auto& entry : node) {
      options.emplace_back(entry.first.as<std::string>(), entry.second.as<std::string>());
    }
  } catch (const YAML::Exception& error) {
    throw CheckpointError(std::string("configuration's env.options: ") + error.what());
  }
  return options;
}

}  // namespace upkie_rl
