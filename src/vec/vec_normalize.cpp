#include "vec/vec_normalize.hpp"

#include "vec/normalization_state.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace upkie_rl {

namespace key = normalization_state;

VecNormalize::VecNormalize(std::unique_ptr<VectorEnv> venv, const NormalizeConfig& config)
    : venv_(venv ? std::move(venv) : throw std::invalid_argument("VecNormalize: null env")),
      config_(config),
      observation_size_(venv_->observation_space().size()),
      observation_rms_(observation_size_),
      return_rms_(1),
      merged_observation_rms_(observation_size_),
      merged_return_rms_(1) {
  check_normalize_config(config_);
  const std::size_t n = venv_->num_envs();
  returns_.assign(n, 0.0);
  raw_observations_.assign(n * observation_size_, 0.0f);
  raw_rewards_.assign(n, 0.0f);
  observations_.assign(n * observation_size_, 0.0f);
  step_.observations.assign(n * observation_size_, 0.0f);
  step_.final_observations.assign(n * observation_size_, 0.0f);
}

void VecNormalize::set_statistics_mirror(const SignedPermutation& mirror) {
  if (mirror.size() != observation_size_) {
    throw std::invalid_argument("VecNormalize: a mirror of " + std::to_string(mirror.size()) +
                                " components for observations of " +
                                std::to_string(observation_size_));
  }
  statistics_mirror_ = mirror;
  mirrored_observations_.assign(raw_observations_.size(), 0.0f);
}

void VecNormalize::update_observation_statistics() {
  if (!training_ || !config_.observations) return;
  observation_rms_.update(raw_observations_);
  if (statistics_mirror_) {
    statistics_mirror_->apply(raw_observations_, mirrored_observations_);
    observation_rms_.update(mirrored_observations_);
  }
}

void VecNormalize::normalize_observations(std::span<const float> raw,
                                          std::span<float> normalized) const {
  if (raw.size() != normalized.size() || raw.size() % observation_size_ != 0) {
    throw std::invalid_argument("VecNormalize: observations of size " + std::to_string(raw.size()) +
                                " are not rows of " + std::to_string(observation_size_));
  }
  if (!config_.observations) {
    std::copy(raw.begin(), raw.end(), normalized.begin());
    return;
  }
  const std::vector<double>& mean = observation_rms_.mean();
  const std::vector<double>& var = observation_rms_.var();
  const double clip = config_.clip_observations;
  for (std::size_t k = 0; k < raw.size(); ++k) {
    const std::size_t j = k % observation_size_;
    const double value = (raw[k] - mean[j]) / std::sqrt(var[j] + config_.epsilon);
    normalized[k] = static_cast<float>(std::clamp(value, -clip, clip));
  }
}

std::span<const float> VecNormalize::reset(std::optional<std::uint64_t> seed) {
  const std::span<const float> raw = venv_->reset(seed);
  std::copy(raw.begin(), raw.end(), raw_observations_.begin());
  std::fill(returns_.begin(), returns_.end(), 0.0);
  update_observation_statistics();
  normalize_observations(raw_observations_, observations_);
  return observations_;
}

const VectorStep& VecNormalize::step(std::span<const float> actions) {
  const VectorStep& inner = venv_->step(actions);
  const std::size_t n = num_envs();
  std::copy(inner.observations.begin(), inner.observations.end(), raw_observations_.begin());
  std::copy(inner.rewards.begin(), inner.rewards.end(), raw_rewards_.begin());
  step_.terminated = inner.terminated;
  step_.truncated = inner.truncated;
  step_.episode_returns = inner.episode_returns;
  step_.episode_lengths = inner.episode_lengths;
  step_.episode_reward_terms = inner.episode_reward_terms;
  step_.rewards = inner.rewards;

  update_observation_statistics();
  normalize_observations(raw_observations_, step_.observations);
  for (std::size_t i = 0; i < n; ++i) {
    if (!inner.terminated[i] && !inner.truncated[i]) continue;
    const std::size_t offset = i * observation_size_;
    normalize_observations(
        std::span<const float>(inner.final_observations).subspan(offset, observation_size_),
        std::span<float>(step_.final_observations).subspan(offset, observation_size_));
  }

  if (training_) {
    for (std::size_t i = 0; i < n; ++i) returns_[i] = returns_[i] * config_.gamma + raw_rewards_[i];
    return_rms_.update(returns_);
    if (config_.rewards) {
      const double scale = std::sqrt(return_rms_.var()[0] + config_.epsilon);
      const double clip = config_.clip_rewards;
      for (std::size_t i = 0; i < n; ++i) {
        step_.rewards[i] = static_cast<float>(std::clamp(raw_rewards_[i] / scale, -clip, clip));
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (inner.terminated[i] || inner.truncated[i]) returns_[i] = 0.0;
  }
  return step_;
}

nlohmann::json VecNormalize::state() const {
  return {{key::kObservationStatistics, observation_rms_.to_json()},
          {key::kReturnStatistics, return_rms_.to_json()},
          {key::kConfig, normalize_config_to_json(config_)}};
}

void VecNormalize::load_state(const nlohmann::json& state) {
  if (!state.is_object()) throw std::invalid_argument("normalisation state must be an object");
  for (const char* name : {key::kObservationStatistics, key::kReturnStatistics, key::kConfig}) {
    if (!state.contains(name)) throw std::invalid_argument(std::string("missing key ") + name);
  }
  RunningMeanStd observations(observation_size_);
  observations.from_json(state.at(key::kObservationStatistics), key::kObservationStatistics);
  RunningMeanStd returns(1);
  returns.from_json(state.at(key::kReturnStatistics), key::kReturnStatistics);
  const NormalizeConfig config = normalize_config_from_json(state.at(key::kConfig));
  observation_rms_ = std::move(observations);
  return_rms_ = std::move(returns);
  merged_observation_rms_ = observation_rms_;
  merged_return_rms_ = return_rms_;
  config_ = config;
}

void VecNormalize::merge_statistics(
    const std::function<void(std::span<double>)>& sum_over_processes) {
  observation_rms_.merge_across_processes(merged_observation_rms_, sum_over_processes);
  return_rms_.merge_across_processes(merged_return_rms_, sum_over_processes);
}

}  // namespace upkie_rl
