#pragma once
/// @file
/// Vector environments: n environments stepped together with automatic reset (SB3
/// semantics). Observations are float32 rows, one per environment.

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "envs/spaces/box_space.hpp"
#include "envs/spaces/mirror_symmetry.hpp"
#include "sim/observation.hpp"

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
  /// num_envs x VectorEnv::reward_term_names().size(): each reward term summed over an
  /// episode that ended at this step (raw, like episode_returns).
  std::vector<double> episode_reward_terms;
};

/// When an environment whose episode ended is reset (Gymnasium's autoreset modes).
enum class AutoresetMode {
  /// In the step that ends the episode (SB3 VecEnv, our trainer): the returned observation
  /// is the new episode's first, the last one is in final_observations.
  kSameStep,
  /// In the next step (Gymnasium 1.x vector envs): the step that ends the episode returns its
  /// last observation; the next step resets that environment instead of stepping it,
  /// ignores its action, and returns reward 0, terminated and truncated false.
  kNextStep,
};

/// n environments of the same kind, stepped in lockstep.
class VectorEnv {
 public:
  virtual ~VectorEnv() = default;

  virtual std::size_t num_envs() const = 0;
  virtual const BoxSpace& observation_space() const = 0;
  virtual const BoxSpace& action_space() const = 0;

  /// Resets every environment, env i with seed + i (without a seed, each environment's
  /// generator continues), and returns the observations (num_envs x obs_dim).
  virtual std::span<const float> reset(std::optional<std::uint64_t> seed) = 0;

  /// Steps every environment with its row of `actions` (num_envs x action_dim); envs
  /// whose episode ended are reset as the autoreset mode says (same step by default).
  virtual const VectorStep& step(std::span<const float> actions) = 0;

  /// The environments' Env::reward_term_names() (empty when they do not break the reward
  /// down).
  virtual std::span<const std::string_view> reward_term_names() const { return {}; }

  /// The environments' Env::mirror_symmetry() (nullptr when they declare none).
  virtual const MirrorSymmetry* mirror_symmetry() const { return nullptr; }

  /// Env::set_randomization_scale on every environment (between steps, never during one);
  /// vector envs of environments without randomisation ignore it.
  virtual void set_randomization_scale(double scale) { static_cast<void>(scale); }

  /// The full observation of environment i after the last reset or step (after an
  /// auto-reset, the new episode's), or nullptr when it has none.
  virtual const Observation* full_observation(std::size_t i) const {
    static_cast<void>(i);
    return nullptr;
  }
};

}  // namespace upkie_rl
