#include "envs/randomization/action_lag.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "envs/core/shared_options.hpp"
#include "sim/random_draws.hpp"

namespace upkie_rl {
namespace {

constexpr std::uint64_t kActionLagStream = 3;
constexpr int kMaxDelaySteps = 10000;
constexpr double kMaxDelayTime = 1.0;  ///< [s]

/// `settings` (valid) with a delay_time as the nearest whole number of `step_duration`
/// (positive) steps.
/// @throws std::invalid_argument when that is more than kMaxDelaySteps.
ActionLagSettings in_steps(ActionLagSettings settings, double step_duration) {
  if (settings.delay_time <= 0.0) return settings;
  const double steps = std::round(settings.delay_time / step_duration);
  if (steps > kMaxDelaySteps) {
    throw std::invalid_argument(
        "ActionLag: action_delay_time " + std::to_string(settings.delay_time) + " s is more than " +
        std::to_string(kMaxDelaySteps) + " steps of " + std::to_string(step_duration) + " s");
  }
  settings.delay_steps = static_cast<int>(steps);
  settings.delay_time = 0.0;
  return settings;
}

}  // namespace

std::string ActionLagSettings::problem() const {
  const double low = time_constant_min;
  const double high = time_constant_max;
  if (!(std::isfinite(low) && std::isfinite(high) && low >= 0.0 && high >= low)) {
    return "ActionLag: need 0 <= action_lag_min <= action_lag_max, got " + std::to_string(low) +
           " and " + std::to_string(high);
  }
  if (delay_steps < 0 || delay_steps > kMaxDelaySteps) {
    return "ActionLag: action_delay must be in [0, " + std::to_string(kMaxDelaySteps) + "], got " +
           std::to_string(delay_steps);
  }
  if (delay_steps_max < 0 || delay_steps_max > kMaxDelaySteps) {
    return "ActionLag: action_delay_max must be in [0, " + std::to_string(kMaxDelaySteps) +
           "], got " + std::to_string(delay_steps_max);
  }
  if (!(std::isfinite(delay_time) && delay_time >= 0.0 && delay_time <= kMaxDelayTime)) {
    return "ActionLag: action_delay_time must be in [0, " + std::to_string(kMaxDelayTime) +
           "] s, got " + std::to_string(delay_time);
  }
  if (delay_time > 0.0 && (delay_steps > 0 || delay_steps_max > 0)) {
    return "ActionLag: action_delay_time and action_delay or action_delay_max are both set; "
           "give the delay in seconds or in steps";
  }
  return "";
}

void ActionLagSettings::validate() const { throw_problem(problem()); }

void ActionLagSettings::declare_options(OptionTable& table) {
  table.add_real("action_lag_min", &time_constant_min, 0.0, kOptionHuge,
                 "first-order action lag: time constant drawn in U(min, max) at reset [s]");
  table.add_real("action_lag_max", &time_constant_max, 0.0, kOptionHuge,
                 "largest action lag time constant [s], 0 for no lag");
  table.add_integer("action_delay", &delay_steps, 0, kMaxDelaySteps,
                    "steps between an action and its application");
  table.add_integer("action_delay_max", &delay_steps_max, 0, kMaxDelaySteps,
                    "largest delay drawn per episode in U{action_delay..max} [steps], 0 for "
                    "a fixed delay");
  table.add_real("action_delay_time", &delay_time, 0.0, kMaxDelayTime,
                 "delay between an action and its application [s], rounded to whole steps "
                 "(instead of action_delay: the same time at any rate)");
  table.add_rule([this] { return problem(); });
}

ActionLag::ActionLag(const ActionLagSettings& settings, double step_duration)
    : settings_(settings), step_duration_(step_duration) {
  settings_.validate();
  if (!(std::isfinite(step_duration) && step_duration > 0.0)) {
    throw std::invalid_argument("ActionLag: the step must be positive, got " +
                                std::to_string(step_duration) + " s");
  }
  settings_ = in_steps(settings_, step_duration);
  // The largest delay the randomisation scale (at most 1) can draw.
  delay_line_ = ServoDelayLine(static_cast<std::size_t>(settings_.largest_delay()));
}

void ActionLag::reset(std::optional<std::uint64_t> seed, double randomization_scale) {
  if (seed) generator_.seed(derive_seed(*seed, kActionLagStream));
  time_constant_ = randomization_scale * uniform_between(generator_, settings_.time_constant_min,
                                                         settings_.time_constant_max);
  const int drawn_delay =
      settings_.largest_delay() > settings_.delay_steps
          ? uniform_integer(generator_, settings_.delay_steps, settings_.largest_delay())
          : settings_.delay_steps;
  delay_ = static_cast<int>(std::lround(randomization_scale * drawn_delay));
  lag_ = ServoTargetLag::step_mean(time_constant_, step_duration_);
  started_ = false;
}

const ServoAction& ActionLag::apply(const ServoAction& sent) {
  if (!started_) {
    // The episode's first command fills the delay line and the filter.
    delay_line_.reset(static_cast<std::size_t>(delay_), sent);
    filtered_ = sent;
    started_ = true;
  }
  const ServoAction& delayed = delay_line_.push(sent);
  if (!lag_.any()) return delayed;
  lag_.step(delayed, filtered_, applied_);
  return applied_;
}

}  // namespace upkie_rl
