#include "policy/model_header.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <type_traits>

#include "envs/registry/registry.hpp"
#include "policy/checkpoint_file.hpp"
#include "policy/checkpoint_header.hpp"
#include "policy/network_limits.hpp"

namespace upkie_rl {

namespace {

/// The keys of the header's "policy" entry, each once, for the writer and the reader.
template <typename Shape, typename Visitor>
void visit_policy_shape_fields(Shape& shape, Visitor&& visit) {
  using namespace checkpoint_header;
  visit(kObservationSize, shape.observation_size);
  visit(kActionSize, shape.action_size);
  visit(kActorHiddenSizes, shape.actor_hidden_sizes);
  visit(kCriticHiddenSizes, shape.critic_hidden_sizes);
  visit(kActivation, shape.activation);
}

}  // namespace

nlohmann::json policy_shape_to_json(const PolicyShape& shape) {
  nlohmann::json json = nlohmann::json::object();
  visit_policy_shape_fields(shape, [&](const char* key, const auto& value) {
    if constexpr (std::is_same_v<std::decay_t<decltype(value)>, Activation>) {
      json[key] = activation_name(value);
    } else {
      json[key] = value;
    }
  });
  return json;
}

PolicyShape policy_shape_from_json(const nlohmann::json& json) {
  PolicyShape shape;
  visit_policy_shape_fields(shape, [&](const char* key, auto& value) {
    using Value = std::decay_t<decltype(value)>;
    if constexpr (std::is_same_v<Value, Activation>) {
      value = parse_activation(json.at(key).get<std::string>());
    } else {
      value = json.at(key).get<Value>();
    }
  });
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
  const auto found = header.find(checkpoint_header::kConfig);
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
  // A checkpoint made before an option's default changed means its former default.
  try {
    return with_recorded_defaults(checkpoint_env_id(header), options);
  } catch (const std::invalid_argument&) {
    return options;  // an id this build does not know: checked where it is used
  }
}

}  // namespace upkie_rl
