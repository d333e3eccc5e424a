#pragma once
/// @file
/// A trained policy for deployment, without libtorch: the deterministic action (the actor's
/// mean, clipped to the action bounds) of an observation normalised with the frozen training
/// statistics, read from a final model or checkpoint of `upkie-rl train`. What
/// `upkie-rl rollout --model`, the Python package and a robot run.

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "envs/spaces/box_space.hpp"
#include "policy/checkpoint_file.hpp"
#include "policy/mlp.hpp"
#include "policy/model_header.hpp"
#include "policy/observation_normalizer.hpp"

namespace upkie_rl {

/// One loaded policy. Not thread-safe: act() reuses buffers made at load.
class DeployedPolicy {
 public:
  /// Reads a model or checkpoint through the checkpoint gate (policy/checkpoint_gate.hpp).
  /// Throws CheckpointError naming the file and the problem (missing, truncated, corrupted,
  /// not a model, unknown version, inconsistent sizes, non-finite values).
  static DeployedPolicy load(const std::filesystem::path& path);

  /// From a checkpoint file's contents, checked by check_checkpoint; `where` names it in
  /// errors.
  static DeployedPolicy from_checkpoint(const CheckpointFile& file, const std::string& where);

  /// Environment id the policy was trained on.
  const std::string& env_id() const { return env_id_; }
  /// Environment options it was trained with (env.options of the configuration).
  const EnvOptions& env_options() const { return env_options_; }
  const BoxSpace& observation_space() const { return observation_space_; }
  const BoxSpace& action_space() const { return action_space_; }
  const PolicyShape& shape() const { return shape_; }
  const ObservationNormalizer& normalizer() const { return normalizer_; }
  /// Every parameter (policy/parameter_layout.hpp), actor first.
  const std::vector<float>& parameters() const { return parameters_; }
  /// The actor network in parameters(): what act() runs and the exporters write.
  const Mlp& actor() const { return actor_; }

  /// Throws CheckpointError saying how the environment's spaces differ from the model's.
  void check_spaces(const BoxSpace& observation_space, const BoxSpace& action_space) const;

  /// Writes the deterministic action for one raw observation. Allocation-free (unless it
  /// throws). Never writes a non-finite action: the checkpoint gate proves the network
  /// finite for observations in range (policy/network_output_bound.hpp), and beyond that
  /// a non-finite output is refused.
  /// @throws std::invalid_argument on wrong sizes or a non-finite observation component.
  /// @throws PolicyOutputError naming the action component when the output is not finite.
  void act(std::span<const float> observation, std::span<float> action);

  /// act() for each row of `observations` (n x observation size) into `actions`
  /// (n x action size). Allocation-free.
  /// @throws std::invalid_argument unless both are n rows of their size, and what act()
  ///         throws.
  void act_batch(std::span<const float> observations, std::span<float> actions);

 private:
  DeployedPolicy() = default;

  std::string env_id_;
  EnvOptions env_options_;
  BoxSpace observation_space_;
  BoxSpace action_space_;
  PolicyShape shape_;
  ObservationNormalizer normalizer_;
  std::vector<float> parameters_;
  Mlp actor_;                   // In parameters_.
  std::vector<float> input_;    // Normalised observation.
  std::vector<float> scratch_;  // Hidden layers' outputs (Mlp::scratch_size()).
};

}  // namespace upkie_rl
