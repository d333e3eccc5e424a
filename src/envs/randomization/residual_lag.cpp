#include "envs/randomization/residual_lag.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "base/number_text.hpp"
#include "sim/random_draws.hpp"

namespace upkie_rl {
namespace {

/// Stream of the residual's lag, derived from a reset's seed.
constexpr std::uint64_t kResidualLagStream = 13;

}  // namespace

ResidualLag::ResidualLag(double time_constant, double max_draw, double step_duration,
                         std::size_t size)
    : max_draw_(max_draw), step_duration_(step_duration), state_(size, 0.0) {
  const auto refuse = [](const std::string& name, double value, const char* need) {
    throw std::invalid_argument(name + ": need " + need + ", got " + shortest_text(value));
  };
  if (!(std::isfinite(time_constant) && time_constant >= 0.0))
    refuse("residual_filter", time_constant, "a time constant >= 0 [s]");
  if (!(std::isfinite(max_draw) && max_draw >= 0.0))
    refuse("residual_lag_max", max_draw, "a time constant >= 0 [s]");
  if (!(std::isfinite(step_duration) && step_duration > 0.0))
    refuse("residual_filter", step_duration, "an agent step > 0 [s]");
  // A policy is deployed with the nominal time constant: a training that draws one must
  // have drawn that one too.
  if (max_draw > 0.0 && time_constant > max_draw) {
    throw std::invalid_argument(
        "residual_filter " + shortest_text(time_constant) +
        " s is outside the time constants residual_lag_max draws in training, [0, " +
        shortest_text(max_draw) + "] s: the policy would run with a filter it never trained with");
  }
  // Without a draw, the nominal time constant holds for every episode (reset keeps it).
  time_constant_ = time_constant;
  lag_ = ServoTargetLag::step_mean(time_constant_, step_duration_);
}

void ResidualLag::reset(std::optional<std::uint64_t> seed, double randomization_scale) {
  if (seed) generator_.seed(derive_seed(*seed, kResidualLagStream));
  if (max_draw_ > 0.0) {
    time_constant_ = randomization_scale * uniform_between(generator_, 0.0, max_draw_);
    lag_ = ServoTargetLag::step_mean(time_constant_, step_duration_);
  }
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
