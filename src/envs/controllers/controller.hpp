#pragma once
/// @file
/// Controller: what chooses an environment's actions in `upkie-rl rollout` (built-in laws,
/// trained policies).

#include <span>

namespace upkie_rl {

/// Maps an observation to an action, both flat float vectors of the environment's spaces.
class Controller {
 public:
  virtual ~Controller() = default;

  /// Called at the start of each episode (controllers with memory clear it).
  virtual void reset() {}

  /// Writes the action for `observation` into `action` (allocation-free).
  virtual void act(std::span<const float> observation, std::span<float> action) = 0;
};

}  // namespace upkie_rl
