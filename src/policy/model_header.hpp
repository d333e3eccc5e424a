#pragma once
/// @file
/// The entries of a checkpoint header that the trainer writes (rl/runs/ppo_checkpoint.hpp) and a
/// deployed policy reads back: the format tag, the resolved configuration, and the shape of
/// the actor-critic ("policy").

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "envs/core/env_options.hpp"

#include "policy/activation.hpp"

namespace upkie_rl {

/// The header's "format" of every checkpoint and final model of `upkie-rl train`.
inline constexpr const char* kCheckpointFormat = "upkie-rl checkpoint";

/// The sizes and activation of the actor and critic MLPs (the header's "policy" entry).
struct PolicyShape {
  std::int64_t observation_size = 0;
  std::int64_t action_size = 0;
  std::vector<std::int64_t> actor_hidden_sizes;
  std::vector<std::int64_t> critic_hidden_sizes;
  Activation activation = Activation::kReLU;

  bool operator==(const PolicyShape&) const = default;
};

/// The header's "policy" entry: {observation_size, action_size, actor_hidden_sizes,
/// critic_hidden_sizes, activation (its name)}, keys declared once in
/// visit_policy_shape_fields.
nlohmann::json policy_shape_to_json(const PolicyShape& shape);

/// Inverse of policy_shape_to_json. Throws CheckpointError on sizes outside
/// policy/network_limits.hpp,
/// std::invalid_argument on an unknown activation, nlohmann::json errors on missing keys.
PolicyShape policy_shape_from_json(const nlohmann::json& json);

/// The resolved training configuration (YAML text, the header's "config"). Throws
/// CheckpointError if absent.
std::string checkpoint_config_yaml(const nlohmann::json& header);

/// The environment id of that configuration (key env.id), read without the trainer's
/// configuration parser. Throws CheckpointError if absent.
std::string checkpoint_env_id(const nlohmann::json& header);

/// The environment options (env.options) of the training configuration, in order, preceded
/// by the former defaults of the options it does not name that changed since
/// (envs/registry/registry.hpp with_recorded_defaults: a velocity policy of before the height
/// command reads height_command=false leg_action_scale=0.5); empty when it has none.
/// @throws CheckpointError when the configuration is missing or env.options is malformed.
EnvOptions checkpoint_env_options(const nlohmann::json& header);

}  // namespace upkie_rl
