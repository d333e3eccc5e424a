#include "envs/servos_task_env.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace upkie_rl {

ServosTaskEnv::ServosTaskEnv(std::unique_ptr<ServosEnv> servos, const ServosTaskConfig& config)
    : ServosWrapperEnv(std::move(servos), "ServosTaskEnv"),
      config_(config),
      task_(config.reward, config.termination) {
  for (std::size_t i = 0; i < kNumServos; ++i) {
    const std::string joint(kServoNames[i]);
    const BoxSpace& servo_observation = servos_->observation_dict_space().entries[i].second;
    action_space_.add(joint, -1.0f, 1.0f);
    for (std::size_t key = 0; key < 2; ++key) {  // position, velocity
      observation_space_.add(joint + "." + servo_observation.names[key], servo_observation.low[key],
                             servo_observation.high[key]);
    }
  }
}

void ServosTaskEnv::servo_action_from_normalized(std::span<const float> normalized,
                                                 ServoAction& action) const {
  const RobotModel& model = servos_->model();
  for (std::size_t i = 0; i < kNumServos; ++i) {
    const JointLimits& limits = model.servo_limits(i);
    const double u = normalized[i];
    ServoCommand& command = action[i];
    command.feedforward_torque = 0.0;
    command.maximum_torque = limits.effort;
    if (is_wheel(i)) {
      command.position = std::numeric_limits<double>::quiet_NaN();
      command.velocity = u * limits.velocity;
      command.kp_scale = config_.wheel_kp_scale;
      command.kd_scale = config_.wheel_kd_scale;
    } else {
      command.position = limits.lower + 0.5 * (u + 1.0) * (limits.upper - limits.lower);
      command.velocity = 0.0;
      command.kp_scale = config_.leg_kp_scale;
      command.kd_scale = config_.leg_kd_scale;
    }
  }
}

double ServosTaskEnv::action_magnitude(const ServoAction& action) {
  double magnitude = 0.0;
  for (std::size_t i = 0; i < kNumServos; ++i) {
    magnitude += is_wheel(i) ? std::abs(action[i].velocity) : std::abs(action[i].position);
  }
  return magnitude;
}

void ServosTaskEnv::write_observation(const Observation& full, std::span<float> observation) const {
  if (observation.size() != 2 * kNumServos) {
    throw std::invalid_argument("ServosTaskEnv: observation buffer has " +
                                std::to_string(observation.size()) + " components, expected 12");
  }
  for (std::size_t i = 0; i < kNumServos; ++i) {
    observation[2 * i] = static_cast<float>(full.servo[i].position);
    observation[2 * i + 1] = static_cast<float>(full.servo[i].velocity);
  }
}

void ServosTaskEnv::reset(std::optional<std::uint64_t> seed, std::span<float> observation) {
  const Observation& full = servos_->reset_servos(seed);
  task_.reset(full);
  write_observation(full, observation);
}

StepResult ServosTaskEnv::step(std::span<const float> action, std::span<float> observation) {
  clamp_to_space(action_space_, action, clamped_);
  servo_action_from_normalized(clamped_, servo_action_);
  const Observation& full = servos_->step_servos(servo_action_);
  write_observation(full, observation);
  return task_.evaluate(full, action_magnitude(servo_action_));
}

}  // namespace upkie_rl
