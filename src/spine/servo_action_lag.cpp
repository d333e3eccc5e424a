#include "spine/servo_action_lag.hpp"

#include <algorithm>
#include <cmath>

#include "base/number_text.hpp"
#include "spine/spine_error.hpp"

namespace upkie_rl {
namespace {

/// Largest delay [steps]: 100 s at 1 kHz, far beyond any robot's, bounding the queue.
constexpr int kMaximumDelaySteps = 100000;
/// Largest time constant [s]: a motor that slow could not balance anything.
constexpr double kMaximumTimeConstant = 10.0;

}  // namespace

std::string ServoActionLagSettings::problem() const {
  if (delay_steps < 0 || delay_steps > kMaximumDelaySteps) {
    return "action delay must be in [0, " + std::to_string(kMaximumDelaySteps) +
           "] simulation steps, got " + std::to_string(delay_steps);
  }
  if (!(time_constant >= 0.0 && time_constant <= kMaximumTimeConstant)) {
    return "action lag must be in [0, " + shortest_text(kMaximumTimeConstant) + "] s, got " +
           shortest_text(time_constant);
  }
  if (!(step_duration > 0.0 && std::isfinite(step_duration))) {
    return "the simulation step must be positive and finite, got " + shortest_text(step_duration);
  }
  return "";
}

ServoActionLag::ServoActionLag(const ServoActionLagSettings& settings) : settings_(settings) {
  if (const std::string problem = settings.problem(); !problem.empty()) throw SpineError(problem);
  lag_ = ServoTargetLag::step_end(settings.time_constant, settings.step_duration);
  delay_line_ = ServoDelayLine(static_cast<std::size_t>(settings.delay_steps));
}

void ServoActionLag::reset(const ServoAction& initial) {
  delay_line_.reset(static_cast<std::size_t>(settings_.delay_steps), initial);
  filtered_ = initial;
  applied_ = initial;
}

const ServoAction& ServoActionLag::apply(const ServoAction& sent) {
  // Delay: the command sent delay_steps ago leaves the line, this one enters it.
  const ServoAction& delayed = delay_line_.push(sent);
  // Lag: the targets follow the delayed command; gains and limits are taken as they are.
  if (!lag_.any()) return delayed;
  lag_.step(delayed, filtered_, applied_);
  return applied_;
}

}  // namespace upkie_rl
