#include "envs/randomization/residual_lag.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/random_draws.hpp"

namespace upkie_rl {
namespace {

/// Stream of the residual's lag, derived from a reset's seed.
constexpr std::uint64_t kResidualLagStream = 13;

}  // namespace

ResidualLag::ResidualLag(double max_time_constant, double step_duration, std::size_t size)
    : max_time_constant_(max_time_constant), step_duration_(step_duration), state_(size, 0.0) {
  if (!(std::isfinite(max_time_constant) && max_time_constant > 0.0 &&
        std::isfinite(step_duration) && step_duration > 0.0)) {
    throw std::invalid_argument("residual_lag_max: need a time constant > 0 and a step > 0, got " +
                                std::to_string(max_time_constant) + " and " +
                                std::to_string(step_duration) + " s");
  }
}

void ResidualLag::reset(std::optional<std::uint64_t> seed, double randomization_scale) {
  if (seed) generator_.seed(derive_seed(*seed, kResidualLagStream));
  time_constant_ = randomization_scale * uniform_between(generator_, 0.0, max_time_constant_);
  lag_ = ServoTargetLag::step_mean(time_constant_, step_duration_);
  std::fill(state_.begin(), state_.end(), 0.0);
}

void ResidualLag::apply(std::span<float> action) {
  if (!lag_.any()) return;
  for (std::size_t i = 0; i < action.size() && i < state_.size(); ++i) {
    double applied = 0.0;
    lag_.step_target(action[i], state_[i], applied);
    action[i] = static_cast<float>(applied);
  }
}

}  // namespace upkie_rl
