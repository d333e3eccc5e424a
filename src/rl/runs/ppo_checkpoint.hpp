#pragma once
/// @file
/// What a PPO checkpoint holds and how a learner is restored from one: the resolved
/// configuration, counters and random state, policy weights, Adam moments, normalisation
/// statistics and the spaces the policy was trained on.

#include <nlohmann/json.hpp>

#include "envs/spaces/box_space.hpp"
#include "policy/model_header.hpp"
#include "policy/space_json.hpp"
#include "rl/ppo/ppo.hpp"
#include "rl/runs/checkpoint.hpp"

namespace upkie_rl {

/// Captures `ppo` with the environment's normalisation statistics (`normalization`, the
/// VecNormalize state, or null when training without normalisation) and `extra` header
/// fields (e.g. the trainer's own counters).
Checkpoint make_ppo_checkpoint(const Ppo& ppo, const nlohmann::json& normalization,
                               const nlohmann::json& extra = nlohmann::json::object());

/// Restores weights, optimiser state, counters and random state into `ppo`. Throws
/// CheckpointError if the checkpoint's policy shape or spaces differ from `ppo`'s.
void restore_ppo_checkpoint(Ppo& ppo, const Checkpoint& checkpoint);

}  // namespace upkie_rl
