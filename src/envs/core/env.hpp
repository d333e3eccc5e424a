#pragma once
/// @file
/// The Gymnasium-style environment interface on flat float vectors: what vector envs and
/// the trainer step. Environments know nothing about threads.

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "envs/spaces/box_space.hpp"
#include "envs/spaces/mirror_symmetry.hpp"
#include "sim/observation.hpp"

namespace upkie_rl {

/// What one step returns besides the observation, which is written in place.
struct StepResult {
  double reward = 0.0;
  bool terminated = false;  ///< The task ended (fall, limits): no bootstrap.
  bool truncated = false;   ///< Time limit: the value of the last observation bootstraps.
};

/// Checks a randomisation scale (Env::set_randomization_scale).
/// @throws std::invalid_argument unless it is in [0, 1].
inline void check_randomization_scale(double scale) {
  if (!(scale >= 0.0 && scale <= 1.0)) {
    throw std::invalid_argument("randomization scale must be in [0, 1], got " +
                                std::to_string(scale));
  }
}

/// An environment stepped with a flat float action and giving a flat float observation.
///
/// Gymnasium's `reset(seed, options) -> (observation, info)` maps to reset() then
/// full_observation() (the info); options are given once, at construction (see
/// envs/registry/registry.hpp). `step(action) -> (observation, reward, terminated, truncated,
/// info)` maps to step() (observation written in place, the rest in StepResult) then
/// full_observation().
class Env {
 public:
  virtual ~Env() = default;

  virtual const BoxSpace& observation_space() const = 0;
  virtual const BoxSpace& action_space() const = 0;

  /// Starts an episode and writes its first observation into `observation`
  /// (size observation_space().size()). A seed re-seeds the environment's generator;
  /// without one the generator continues (an environment never seeded starts at seed 0).
  virtual void reset(std::optional<std::uint64_t> seed, std::span<float> observation) = 0;

  /// Applies `action` (size action_space().size()) for one step and writes the next
  /// observation. Actions outside the bounds are clamped; a NaN or infinite component
  /// raises std::invalid_argument naming it (except where an environment documents NaN as
  /// a legal value, like a servo position).
  virtual StepResult step(std::span<const float> action, std::span<float> observation) = 0;

  /// The full observation of the last reset or step (the dictionary `info` carries), or
  /// nullptr when the backend has none.
  virtual const Observation* full_observation() const = 0;

  /// Writes the action that does nothing special (the zero controller): zero by default,
  /// clamped into the bounds; the servos environment gives its neutral servo commands.
  virtual void neutral_action(std::span<float> action) const {
    const BoxSpace& space = action_space();
    for (std::size_t i = 0; i < space.size(); ++i) {
      action[i] = std::clamp(0.0f, space.low[i], space.high[i]);
    }
  }

  /// Multiplies every randomisation bound (initial state, perturbations, noise, action lag,
  /// pushes) by `scale` in [0, 1] from the next reset on: the curriculum of a training run
  /// ramps it from 0 to 1. Wrappers pass it on; environments without randomisation ignore it.
  virtual void set_randomization_scale(double scale) { static_cast<void>(scale); }

  /// Names of the terms the reward is the sum of, when the environment breaks it down
  /// (training logs each term's episode sum); empty otherwise.
  virtual std::span<const std::string_view> reward_term_names() const { return {}; }
  /// The terms of the last step's reward, in the order of reward_term_names().
  virtual std::span<const double> reward_terms() const { return {}; }

  /// How observations and actions map under the robot's left-right mirror, when the
  /// environment declares it (its task is left-right symmetric); nullptr otherwise.
  /// Training with ppo.mirror_augmentation needs it.
  virtual const MirrorSymmetry* mirror_symmetry() const { return nullptr; }

  /// Duration of one step [s].
  virtual double timestep() const = 0;

  /// Physics steps simulated per environment step (0 for backends without physics).
  virtual int physics_steps_per_step() const = 0;
};

}  // namespace upkie_rl
