#pragma once
/// @file
/// VecNormalize: running normalisation of observations and rewards around a vector env
/// (SB3 VecNormalize semantics, training.md section 3).

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <vector>

#include "vec/normalize_config.hpp"
#include "vec/running_mean_std.hpp"
#include "vec/vector_env.hpp"

namespace upkie_rl {

/// Observations: obs_n = clip((obs - mean) / sqrt(var + epsilon), ±clip_observations), with
/// the statistics updated (while training) by every batch of observations the inner env
/// returns, at reset and at each step (post-reset observations), before normalising. The
/// final observations of ended episodes are normalised with the same statistics.
/// Rewards (while training): per env G <- gamma·G + r, the variance of G updated with the
/// batch of G, r_n = clip(r / sqrt(var_G + epsilon), ±clip_rewards), G <- 0 when an
/// episode ends. When not training, statistics are frozen and rewards pass raw.
/// episode_returns / episode_lengths stay raw.
class VecNormalize final : public VectorEnv {
 public:
  /// @throws std::invalid_argument on a null env or a setting out of check_normalize_config's
  /// ranges.
  VecNormalize(std::unique_ptr<VectorEnv> venv, const NormalizeConfig& config);

  /// false: statistics frozen, rewards not normalised (evaluation).
  void set_training(bool training) { training_ = training; }
  bool training() const { return training_; }

  /// From now on, each batch of observations that updates the statistics updates them with
  /// its mirror image too (`mirror` of the observation vector), so that they are
  /// mirror-symmetric (mean = mirror(mean), variances swapped alike) from symmetric ones
  /// (the initial ones): then normalising commutes with mirroring, and a mirrored normalised
  /// observation is the normalised mirrored one (ppo.mirror_augmentation trains on those).
  /// @throws std::invalid_argument when the mirror's size is not the observation size.
  void set_statistics_mirror(const SignedPermutation& mirror);

  /// Normalises observations with the current statistics (no update); `raw` and
  /// `normalized` have the same size, a multiple of the observation size; may alias.
  void normalize_observations(std::span<const float> raw, std::span<float> normalized) const;

  /// Last un-normalised observations (num_envs x obs_dim).
  std::span<const float> raw_observations() const { return raw_observations_; }
  /// Last un-normalised rewards.
  const std::vector<float>& raw_rewards() const { return raw_rewards_; }

  /// Statistics as JSON: {"observations": {"mean","var","count"}, "returns": {...},
  /// "config": {...}}, keys declared in vec/normalization_state.hpp.
  nlohmann::json state() const;
  /// Restores state(); throws std::invalid_argument naming the field on a mismatch (wrong
  /// size, missing key, wrong type). Leaves the object unchanged when it throws.
  void load_state(const nlohmann::json& state);

  /// Makes the statistics those of every process of a data-parallel run
  /// (RunningMeanStd::merge_across_processes on the observations' and the returns'), so
  /// that they are identical on every process. Call it at the same point of every process,
  /// between steps.
  void merge_statistics(const std::function<void(std::span<double>)>& sum_over_processes);

  const VectorEnv& inner() const { return *venv_; }
  const RunningMeanStd& observation_statistics() const { return observation_rms_; }
  const RunningMeanStd& return_statistics() const { return return_rms_; }
  const NormalizeConfig& config() const { return config_; }

  std::size_t num_envs() const override { return venv_->num_envs(); }
  const BoxSpace& observation_space() const override { return venv_->observation_space(); }
  const BoxSpace& action_space() const override { return venv_->action_space(); }
  std::span<const float> reset(std::optional<std::uint64_t> seed) override;
  const Observation* full_observation(std::size_t i) const override {
    return venv_->full_observation(i);
  }
  const VectorStep& step(std::span<const float> actions) override;
  void set_randomization_scale(double scale) override { venv_->set_randomization_scale(scale); }
  std::span<const std::string_view> reward_term_names() const override {
    return venv_->reward_term_names();
  }
  const MirrorSymmetry* mirror_symmetry() const override { return venv_->mirror_symmetry(); }

 private:
  /// Updates the observations' statistics with raw_observations_ (and their mirror image)
  /// while training.
  void update_observation_statistics();

  std::unique_ptr<VectorEnv> venv_;
  NormalizeConfig config_;
  bool training_ = true;
  std::size_t observation_size_;
  RunningMeanStd observation_rms_;
  RunningMeanStd return_rms_;
  // The statistics after the last merge_statistics (or construction, or load_state).
  RunningMeanStd merged_observation_rms_;
  RunningMeanStd merged_return_rms_;
  std::vector<double> returns_;  // Discounted return G per env.
  std::vector<float> raw_observations_;
  std::vector<float> raw_rewards_;
  std::vector<float> observations_;  // Normalised reset output.
  VectorStep step_;
  std::optional<SignedPermutation> statistics_mirror_;
  std::vector<float> mirrored_observations_;  // The mirror of raw_observations_.
};

}  // namespace upkie_rl
