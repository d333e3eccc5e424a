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

/// One target: the state closes state_gain of the gap, the applied value applied_gain.
void follow(double commanded, const ServoTargetLag& lag, double& state, double& applied) {
  if (std::isnan(commanded) || std::isnan(state)) {
    state = commanded;
    applied = commanded;
    return;
  }
  const double gap = commanded - state;
  applied = state + lag.applied_gain * gap;
  state += lag.state_gain * gap;
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

void ServoTargetLag::step(const ServoAction& command, ServoAction& state,
                          ServoAction& applied) const {
  for (std::size_t servo = 0; servo < command.size(); ++servo) {
    const ServoCommand& sent = command[servo];
    ServoCommand& filter = state[servo];
    double position = 0.0;
    double velocity = 0.0;
    double torque = 0.0;
    follow(sent.position, *this, filter.position, position);
    follow(sent.velocity, *this, filter.velocity, velocity);
    follow(sent.feedforward_torque, *this, filter.feedforward_torque, torque);
    ServoCommand& out = applied[servo];
    out = sent;
    out.position = position;
    out.velocity = velocity;
    out.feedforward_torque = torque;
  }
}

}  // namespace upkie_rl
