#pragma once
/// @file
/// Box spaces in checkpoint headers and model metadata.

#include <string>

#include <nlohmann/json.hpp>

#include "envs/spaces/box_space.hpp"

namespace upkie_rl {

/// Box spaces as JSON; infinite bounds are written as the strings "inf" and "-inf".
nlohmann::json space_to_json(const BoxSpace& space);
/// Inverse of space_to_json; throws CheckpointError on a malformed space.
BoxSpace space_from_json(const nlohmann::json& json);

/// Throws CheckpointError if `actual` differs from `expected` in size, names or bounds,
/// saying which component differs. `what` names the space ("observation space").
void check_same_space(const BoxSpace& expected, const BoxSpace& actual, const std::string& what);

}  // namespace upkie_rl
