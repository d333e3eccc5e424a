#pragma once
/// @file
/// A trained policy loaded from a checkpoint or final model file, for deployment: the
/// deterministic action (the Gaussian's mean, clipped to the action bounds) of the
/// observation normalised with the frozen training statistics.

#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "envs/box_space.hpp"
#include "rl/actor_critic.hpp"
#include "rl/observation_normalizer.hpp"

namespace upkie_rl {

class SavedPolicy {
 public:
  /// Loads a checkpoint written by the trainer. Throws CheckpointError naming the file and
  /// the problem (missing, truncated, corrupted, inconsistent).
  static SavedPolicy load(const std::filesystem::path& path);

  /// Environment id the policy was trained on.
  const std::string& env_id() const { return env_id_; }
  const BoxSpace& observation_space() const { return observation_space_; }
  const BoxSpace& action_space() const { return action_space_; }
  const ActorCritic& policy() const { return *policy_; }
  const ObservationNormalizer& normalizer() const { return normalizer_; }

  /// Throws CheckpointError saying how the environment's spaces differ from the model's.
  void check_spaces(const BoxSpace& observation_space, const BoxSpace& action_space) const;

  /// Writes the deterministic action for one raw observation. Allocation-free.
  void act(std::span<const float> observation, std::span<float> action);

 private:
  SavedPolicy() = default;

  std::string env_id_;
  BoxSpace observation_space_;
  BoxSpace action_space_;
  std::unique_ptr<ActorCritic> policy_;
  ObservationNormalizer normalizer_;
  std::unique_ptr<PolicyInference> inference_;
  std::vector<float> normalized_;
};

}  // namespace upkie_rl
