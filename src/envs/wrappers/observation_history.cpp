#include "envs/wrappers/observation_history.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace upkie_rl {
namespace {

// The inner space repeated `length` times, newest first; names after the first block
// carry their age in steps ("gyro.y@t-2").
BoxSpace stacked_space(const BoxSpace& inner, int length) {
  BoxSpace space;
  for (int age = 0; age < length; ++age) {
    const std::string suffix = age == 0 ? "" : "@t-" + std::to_string(age);
    for (std::size_t i = 0; i < inner.size(); ++i) {
      space.add(inner.names.at(i) + suffix, inner.low[i], inner.high[i]);
    }
  }
  return space;
}

}  // namespace

ObservationHistory::ObservationHistory(std::unique_ptr<Env> env, int length)
    : EnvWrapper(std::move(env), "ObservationHistory"), length_(length) {
  if (length < 1 || length > kMaxObservationHistory) {
    throw std::invalid_argument("observation_history must be in [1, " +
                                std::to_string(kMaxObservationHistory) + "], got " +
                                std::to_string(length));
  }
  const BoxSpace& inner = env_->observation_space();
  space_ = stacked_space(inner, length_);
  history_.assign(space_.size(), 0.0f);
  latest_.assign(inner.size(), 0.0f);
  if (const MirrorSymmetry* mirror = env_->mirror_symmetry()) {
    mirror_ = MirrorSymmetry{mirror->observation.repeated(static_cast<std::size_t>(length_)),
                             mirror->action};
  }
}

void ObservationHistory::check_size(std::span<float> observation) const {
  if (observation.size() != space_.size()) {
    throw std::invalid_argument("ObservationHistory: the observation has " +
                                std::to_string(observation.size()) + " components, expected " +
                                std::to_string(space_.size()));
  }
}

void ObservationHistory::reset(std::optional<std::uint64_t> seed, std::span<float> observation) {
  check_size(observation);
  env_->reset(seed, latest_);
  for (auto slot = history_.begin(); slot != history_.end();
       slot += static_cast<std::ptrdiff_t>(latest_.size())) {
    std::copy(latest_.begin(), latest_.end(), slot);
  }
  std::copy(history_.begin(), history_.end(), observation.begin());
}

StepResult ObservationHistory::step(std::span<const float> action, std::span<float> observation) {
  check_size(observation);
  // The inner step writes apart, so that a step that throws leaves the history as it was.
  const StepResult result = env_->step(action, latest_);
  // Every observation ages one step: the oldest falls off the end.
  const auto oldest = history_.end() - static_cast<std::ptrdiff_t>(latest_.size());
  std::copy_backward(history_.begin(), oldest, history_.end());
  std::copy(latest_.begin(), latest_.end(), history_.begin());
  std::copy(history_.begin(), history_.end(), observation.begin());
  return result;
}

}  // namespace upkie_rl
