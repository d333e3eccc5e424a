#pragma once
/// @file
/// Vector environments: n environments stepped together with automatic reset (SB3
/// semantics). Observations are float32 rows, one per environment.

#include <cstdint>
#include <span>
#include <vector>

#include "envs/box_space.hpp"

namespace upkie_rl {

/// The outcome of one vector step. Buffers are sized once and reused.
struct VectorStep {
  std::vector<float> observations;  ///< num_envs x obs_dim; after auto-reset, the new episode's.
  std::vector<float> rewards;       ///< num_envs (possibly normalised by a wrapper).
  std::vector<std::uint8_t> terminated;  ///< num_envs.
  std::vector<std::uint8_t> truncated;   ///< num_envs.
  /// num_envs x obs_dim: the last observation of an episode that ended at this step
  /// (valid where terminated or truncated), before auto-reset.
  std::vector<float> final_observations;
  /// Raw (un-normalised) return and length of an episode that ended at this step.
  std::vector<double> episode_returns;
  std::vector<std::int64_t> episode_lengths;
};

/// n environments of the same kind, stepped in lockstep.
class VectorEnv {
 public:
  virtual ~VectorEnv() = default;

  virtual std::size_t num_envs() const = 0;
  virtual const BoxSpace& observation_space() const = 0;
  virtual const BoxSpace& action_space() const = 0;

  /// Resets every environment, env i with seed + i, and returns the observations
  /// (num_envs x obs_dim).
  virtual std::span<const float> reset(std::uint64_t seed) = 0;

  /// Steps every environment with its row of `actions` (num_envs x action_dim); envs
  /// whose episode ended are reset in the same step.
  virtual const VectorStep& step(std::span<const float> actions) = 0;
};

}  // namespace upkie_rl
