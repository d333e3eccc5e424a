#pragma once
/// @file
/// NormalizeConfig: the settings of VecNormalize (SB3's VecNormalize), declared once, in
/// NormalizeConfig::declare_options, for everything that reads, writes or checks them: the
/// training configuration's normalize.* keys (rl/runs/training_config.hpp: YAML, overrides,
/// `--help` listings) and the "config" entry of the normalisation state
/// (VecNormalize::state(), a checkpoint header's "normalization"), whose keys are the same
/// (vec/normalization_state.hpp).

#include <nlohmann/json_fwd.hpp>
#include <string>

namespace upkie_rl {

class OptionTable;

/// Largest clip_observations and clip_rewards (a finite float32 far beyond any useful value).
inline constexpr double kMaxNormalizationClip = 1e6;

/// Settings of VecNormalize (SB3's defaults, the seed's values).
struct NormalizeConfig {
  bool observations = true;         ///< Normalise observations.
  bool rewards = true;              ///< Normalise rewards (by the std of discounted returns).
  double clip_observations = 10.0;  ///< Normalised observations are clipped to ±it.
  double clip_rewards = 10.0;       ///< Normalised rewards are clipped to ±it.
  double gamma = 0.99;              ///< Discount of the returns whose variance scales rewards.
  double epsilon = 1e-8;            ///< Added to the variances before their square root.

  /// Declares every setting, named `prefix` + its key in the normalisation state
  /// (vec/normalization_state.hpp), with its range and help: prefix "normalize." for the
  /// training configuration, "" for the state's config entry.
  void declare_options(OptionTable& table, const std::string& prefix);
};

/// Throws std::invalid_argument naming the setting ("normalization gamma: ...") unless
/// clip_observations and clip_rewards are in (0, kMaxNormalizationClip], gamma and epsilon
/// in (0, 1] (the ranges of declare_options).
void check_normalize_config(const NormalizeConfig& config);

/// The "config" entry of a normalisation state: {key: value} of every declared setting,
/// booleans and numbers.
nlohmann::json normalize_config_to_json(const NormalizeConfig& config);

/// Reads normalize_config_to_json's output, checked as above; throws std::invalid_argument
/// naming a missing or mistyped key ("config.gamma must be a number").
NormalizeConfig normalize_config_from_json(const nlohmann::json& json);

}  // namespace upkie_rl
