#pragma once
/// @file
/// The VecNormalize state (see VecNormalize::state()) the trainer stores in a model, for the
/// tests that write models by hand.

#include <vector>

#include <nlohmann/json.hpp>

namespace upkie_rl::testing {

/// Observations normalised with these statistics and clipped to ±`clip_observations`.
inline nlohmann::json normalization_state(const std::vector<double>& mean,
                                          const std::vector<double>& var,
                                          double clip_observations) {
  return {{"observations", {{"mean", mean}, {"var", var}, {"count", 10.0}}},
          {"returns", {{"mean", {0.0}}, {"var", {1.0}}, {"count", 10.0}}},
          {"config",
           {{"observations", true},
            {"rewards", true},
            {"clip_observations", clip_observations},
            {"clip_rewards", 10.0},
            {"gamma", 0.99},
            {"epsilon", 1e-8}}}};
}

}  // namespace upkie_rl::testing
