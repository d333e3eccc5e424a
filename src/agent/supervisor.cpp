#include "agent/supervisor.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "agent/agent_error.hpp"

namespace upkie_rl {
namespace {

std::string format_value(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f", value);
  return text;
}

/// Moves `last` towards `target` by at most `max_change`; NaN (no position loop) passes.
double rate_limited(double target, double last, double max_change) {
  if (std::isnan(target) || std::isnan(last)) return target;
  return std::clamp(target, last - max_change, last + max_change);
}

}  // namespace

Supervisor::Supervisor(const SupervisorLimits& limits, std::shared_ptr<const RobotModel> model,
                       double timestep)
    : limits_(limits), model_(std::move(model)), timestep_(timestep) {
  limits_.validate();
  if (!model_) throw AgentError("supervisor: no robot model");
  if (!(timestep > 0.0)) throw AgentError("supervisor: the timestep must be positive");
}

void Supervisor::transition(SupervisorState next, std::string_view reason) {
  if (next == state_) return;
  spdlog::info("supervisor: {} -> {}: {}", supervisor_state_name(state_),
               supervisor_state_name(next), reason);
  state_ = next;
}

void Supervisor::check_observation(const Observation& observation) const {
  const double pitch = observation.base_orientation.pitch;
  const Eigen::Matrix3d& rotation = observation.base_orientation.rotation_base_to_world;
  const double roll = std::atan2(rotation(2, 1), rotation(2, 2));
  if (!std::isfinite(pitch) || !std::isfinite(roll)) {
    throw SupervisorTrip("attitude limit: the measured attitude is not finite");
  }
  if (std::abs(pitch) > limits_.max_pitch) {
    throw SupervisorTrip("attitude limit: pitch " + format_value(pitch) + " rad beyond +-" +
                         format_value(limits_.max_pitch) + " rad");
  }
  if (std::abs(roll) > limits_.max_roll) {
    throw SupervisorTrip("attitude limit: roll " + format_value(roll) + " rad beyond +-" +
                         format_value(limits_.max_roll) + " rad");
  }
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    const JointLimits& joint = model_->servo_limits(servo);
    const ServoObservation& measured = observation.servo[servo];
    const auto name = [servo] { return std::string(kServoNames[servo]); };  // on a trip only
    if (!std::isfinite(measured.position) || !std::isfinite(measured.velocity)) {
      throw SupervisorTrip("joint limit: " + name() + " measurement is not finite");
    }
    if (joint.has_position_limits() &&
        (measured.position < joint.lower - limits_.joint_position_margin ||
         measured.position > joint.upper + limits_.joint_position_margin)) {
      throw SupervisorTrip("joint position limit: " + name() + " at " +
                           format_value(measured.position) + " rad, outside [" +
                           format_value(joint.lower) + ", " + format_value(joint.upper) + "]");
    }
    const double max_velocity = joint.velocity * limits_.joint_velocity_factor;
    if (joint.velocity > 0.0 && std::abs(measured.velocity) > max_velocity) {
      throw SupervisorTrip("joint velocity limit: " + name() + " at " +
                           format_value(measured.velocity) + " rad/s, beyond +-" +
                           format_value(max_velocity) + " rad/s");
    }
  }
}

void Supervisor::check_policy_output(std::span<const float> action, const BoxSpace& space) const {
  for (std::size_t i = 0; i < action.size(); ++i) {
    const float value = action[i];
    const auto name = [&space, i] {
      return i < space.names.size() ? space.names[i] : std::to_string(i);
    };
    if (!std::isfinite(value)) {
      throw SupervisorTrip("policy output: " + name() + " is not finite (" + std::to_string(value) +
                           ")");
    }
    if (value < space.low[i] || value > space.high[i]) {
      throw SupervisorTrip("policy output: " + name() + " = " + std::to_string(value) +
                           " outside its space [" + std::to_string(space.low[i]) + ", " +
                           std::to_string(space.high[i]) + "]");
    }
  }
}

double Supervisor::torque_cap(std::size_t servo) const {
  const double effort = model_->servo_limits(servo).effort;
  return limits_.max_torque > 0.0 ? std::min(limits_.max_torque, effort) : effort;
}

void Supervisor::limit_commands(ServoAction& action) {
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    ServoCommand& command = action[servo];
    const ServoCommand& last = last_sent_[servo];
    command.maximum_torque = std::min(command.maximum_torque, torque_cap(servo));
    command.position = rate_limited(command.position, last.position,
                                    limits_.max_position_command_rate * timestep_);
    command.velocity = rate_limited(command.velocity, last.velocity,
                                    limits_.max_velocity_command_rate * timestep_);
    last_sent_[servo] = command;
  }
}

void Supervisor::reset_commands(const Observation& observation) {
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    last_sent_[servo].position = is_wheel(servo) ? std::numeric_limits<double>::quiet_NaN()
                                                 : observation.servo[servo].position;
    last_sent_[servo].velocity = 0.0;
  }
}

ServoAction Supervisor::stop_action(const Observation& observation) const {
  ServoAction action{};
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    ServoCommand& command = action[servo];
    command.position = is_wheel(servo) ? std::numeric_limits<double>::quiet_NaN()
                                       : observation.servo[servo].position;
    command.velocity = 0.0;
    command.feedforward_torque = 0.0;
    command.kp_scale = is_wheel(servo) ? 0.0 : 1.0;
    command.kd_scale = 1.0;
    command.maximum_torque = torque_cap(servo);
  }
  return action;
}

}  // namespace upkie_rl
