#pragma once
/// @file
/// Frozen observation normalisation for deployment: the statistics VecNormalize saved,
/// applied as obs_n = clip((obs − mean)/√(var + ε), ±clip).

#include <cstddef>
#include <span>
#include <vector>

#include <nlohmann/json.hpp>

namespace upkie_rl {

/// Frozen VecNormalize observation statistics.
class ObservationNormalizer {
 public:
  /// Identity (no normalisation) for observations of `size` components.
  explicit ObservationNormalizer(std::size_t size = 0);

  /// Reads the observation part of a VecNormalize state (see VecNormalize::state()); a null
  /// state gives the identity. Throws std::invalid_argument naming the bad field or a size
  /// different from `size`.
  static ObservationNormalizer from_state(const nlohmann::json& state, std::size_t size);

  bool enabled() const { return enabled_; }
  std::size_t size() const { return mean_.size(); }
  const std::vector<double>& mean() const { return mean_; }
  const std::vector<double>& var() const { return var_; }
  double clip() const { return clip_; }
  double epsilon() const { return epsilon_; }

  /// Normalises rows of observations (raw.size() a multiple of size()); may alias.
  void normalize(std::span<const float> raw, std::span<float> normalized) const;

 private:
  bool enabled_ = false;
  std::vector<double> mean_;
  std::vector<double> var_;
  double clip_ = 10.0;
  double epsilon_ = 1e-8;
};

}  // namespace upkie_rl
