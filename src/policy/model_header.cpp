#include "policy/model_header.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>

#include "policy/checkpoint_file.hpp"
#include "policy/network_limits.hpp"

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
  try {
    check_network_size(shape.observation_size, shape.action_size, shape.actor_hidden_sizes,
                       shape.critic_hidden_sizes, "policy.actor_hidden_sizes",
                       "policy.critic_hidden_sizes");
  } catch (const std::invalid_argument& error) {
    throw CheckpointError(std::string("policy: ") + error.what());
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
