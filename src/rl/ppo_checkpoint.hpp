#pragma once
/// @file
/// What a PPO checkpoint holds and how a learner is restored from one: the resolved
/// configuration, counters and random state, policy weights, Adam moments, normalisation
/// statistics and the spaces the policy was trained on.

#include <nlohmann/json.hpp>

#include "envs/box_space.hpp"
#include "rl/checkpoint.hpp"
#include "rl/ppo.hpp"

namespace upkie_rl {

/// Captures `ppo` with the environment's normalisation statistics (`normalization`, the
/// VecNormalize state, or null when training without normalisation) and `extra` header
/// fields (e.g. the trainer's own counters).
Checkpoint make_ppo_checkpoint(const Ppo& ppo, const nlohmann::json& normalization,
                               const nlohmann::json& extra = nlohmann::json::object());

/// Restores weights, optimiser state, counters and random state into `ppo`. Throws
/// CheckpointError if the checkpoint's policy shape or spaces differ from `ppo`'s.
void restore_ppo_checkpoint(Ppo& ppo, const Checkpoint& checkpoint);

/// The resolved configuration stored in a checkpoint (YAML text).
std::string checkpoint_config_yaml(const Checkpoint& checkpoint);

/// Box spaces as JSON; infinite bounds are written as the strings "inf" and "-inf".
nlohmann::json space_to_json(const BoxSpace& space);
/// Inverse of space_to_json; throws CheckpointError on a malformed space.
BoxSpace space_from_json(const nlohmann::json& json);

/// Throws CheckpointError if `actual` differs from `expected` in size, names or bounds,
/// saying which component differs. `what` names the space ("observation space").
void check_same_space(const BoxSpace& expected, const BoxSpace& actual, const std::string& what);

}  // namespace upkie_rl
