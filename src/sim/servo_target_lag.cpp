#include "sim/servo_target_lag.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace upkie_rl {
namespace {

void check_step(double time_constant, double duration) {
  if (!(std::isfinite(time_constant) && time_constant >= 0.0 && std::isfinite(duration) &&
        duration > 0.0)) {
    throw std::invalid_argument("ServoTargetLag: need a time constant >= 0 and a step > 0, got " +
                                std::to_string(time_constant) + " and " + std::to_string(duration) +
                                " s");
  }
}

}  // namespace

ServoTargetLag ServoTargetLag::step_end(double time_constant, double duration) {
  check_step(time_constant, duration);
  if (time_constant == 0.0) return {};
  const double gain = -std::expm1(-duration / time_constant);
  return {gain, gain};
}

ServoTargetLag ServoTargetLag::step_mean(double time_constant, double duration) {
  check_step(time_constant, duration);
  if (time_constant == 0.0) return {};
  const double ratio = time_constant / duration;
  const double gain = -std::expm1(-duration / time_constant);
  return {gain, 1.0 - ratio * gain};
}

void ServoTargetLag::step_target(double commanded, double& state, double& applied) const {
  if (std::isnan(commanded) || std::isnan(state)) {
    state = commanded;
    applied = commanded;
    return;
  }
  const double gap = commanded - state;
  applied = state + applied_gain * gap;
  state += state_gain * gap;
}

void ServoTargetLag::step(const ServoAction& command, ServoAction& state,
                          ServoAction& applied) const {
  for (std::size_t servo = 0; servo < command.size(); ++servo) {
    const ServoCommand& sent = command[servo];
    ServoCommand& filter = state[servo];
    double position = 0.0;
    double velocity = 0.0;
    double torque = 0.0;
    step_target(sent.position, filter.position, position);
    step_target(sent.velocity, filter.velocity, velocity);
    step_target(sent.feedforward_torque, filter.feedforward_torque, torque);
    ServoCommand& out = applied[servo];
    out = sent;
    out.position = position;
    out.velocity = velocity;
    out.feedforward_torque = torque;
  }
}

}  // namespace upkie_rl
