#pragma once
/// @file
/// The Gymnasium-style environment interface on flat float vectors: what vector envs and
/// the trainer step. Environments know nothing about threads.

#include <cstdint>
#include <optional>
#include <span>

#include "envs/box_space.hpp"
#include "sim/observation.hpp"

namespace upkie_rl {

/// What one step returns besides the observation, which is written in place.
struct StepResult {
  double reward = 0.0;
  bool terminated = false;  ///< The task ended (fall, limits): no bootstrap.
  bool truncated = false;   ///< Time limit: the value of the last observation bootstraps.
};

/// An environment stepped with a flat float action and giving a flat float observation.
class Env {
 public:
  virtual ~Env() = default;

  virtual const BoxSpace& observation_space() const = 0;
  virtual const BoxSpace& action_space() const = 0;

  /// Starts an episode and writes its first observation into `observation`
  /// (size observation_space().size()). A seed re-seeds the environment's generator.
  virtual void reset(std::optional<std::uint64_t> seed, std::span<float> observation) = 0;

  /// Applies `action` (size action_space().size()) for one step and writes the next
  /// observation. Actions outside the bounds are clamped; a NaN or infinite component
  /// raises std::invalid_argument naming it.
  virtual StepResult step(std::span<const float> action, std::span<float> observation) = 0;

  /// The full observation of the last reset or step (the dictionary `info` carries), or
  /// nullptr when the backend has none.
  virtual const Observation* full_observation() const = 0;
};

}  // namespace upkie_rl
