#include "policy/observation_normalizer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "policy/checkpoint_header.hpp"
#include "vec/normalization_state.hpp"
#include "vec/running_mean_std.hpp"

namespace upkie_rl {

namespace key = normalization_state;

ObservationNormalizer::ObservationNormalizer(std::size_t size)
    : mean_(size, 0.0), var_(size, 1.0) {}

ObservationNormalizer ObservationNormalizer::from_state(const nlohmann::json& state,
                                                        std::size_t size) {
  ObservationNormalizer normalizer(size);
  if (state.is_null()) return normalizer;
  try {
    const nlohmann::json& config = state.at(key::kConfig);
    normalizer.enabled_ = config.at(key::kObservations).get<bool>();
    normalizer.clip_ = config.at(key::kClipObservations).get<double>();
    normalizer.epsilon_ = config.at(key::kEpsilon).get<double>();
  } catch (const nlohmann::json::exception& error) {
    throw std::invalid_argument(std::string("normalisation state: ") + error.what());
  }
  RunningMeanStd statistics(size);
  statistics.from_json(
      state.at(key::kObservationStatistics),
      std::string(checkpoint_header::kNormalization) + "." + key::kObservationStatistics);
  normalizer.mean_ = statistics.mean();
  normalizer.var_ = statistics.var();
  return normalizer;
}

void ObservationNormalizer::normalize(std::span<const float> raw,
                                      std::span<float> normalized) const {
  const std::size_t n = size();
  if (n == 0 || raw.size() % n != 0 || normalized.size() != raw.size()) {
    throw std::invalid_argument("ObservationNormalizer: expected rows of " + std::to_string(n) +
                                " values, got " + std::to_string(raw.size()));
  }
  if (!enabled_) {
    std::copy(raw.begin(), raw.end(), normalized.begin());
    return;
  }
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const std::size_t j = i % n;
    const double value = (raw[i] - mean_[j]) / std::sqrt(var_[j] + epsilon_);
    normalized[i] = static_cast<float>(std::clamp(value, -clip_, clip_));
  }
}

}  // namespace upkie_rl
