#pragma once
/// @file
/// Export of the deterministic policy, with its frozen observation normalisation and action
/// clipping, as a TorchScript module that Python loads with `torch.jit.load(path)`:
/// `module(observations)` maps raw observations (obs_size, or batch x obs_size, float32)
/// to actions. The file also carries `metadata.json` (env id, spaces, provenance) as an
/// extra file.

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "envs/spaces/box_space.hpp"
#include "policy/observation_normalizer.hpp"
#include "rl/ppo/actor_critic.hpp"

namespace upkie_rl {

/// Writes the TorchScript module to `path`; `provenance` (policy/provenance.hpp) goes into
/// its metadata. Throws std::runtime_error on failure.
void export_torchscript(const ActorCritic& policy, const ObservationNormalizer& normalizer,
                        const BoxSpace& observation_space, const BoxSpace& action_space,
                        const std::string& env_id, const std::filesystem::path& path,
                        const nlohmann::json& provenance = nlohmann::json::object());

}  // namespace upkie_rl
