#include "envs/kinds/servos_task_env.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include "envs/core/shared_options.hpp"

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
    const double velocity_limit = servos_->model().servo_limits(i).velocity;
    wheel_velocity_scale_[i] = config.max_wheel_velocity > 0.0
                                   ? std::min(config.max_wheel_velocity, velocity_limit)
                                   : velocity_limit;
  }
  if (config.observe_pitch) {
    constexpr auto kPi = static_cast<float>(std::numbers::pi);
    constexpr float kInf = std::numeric_limits<float>::infinity();
    observation_space_.add("base.pitch", -kPi, kPi);
    observation_space_.add("base.pitch_rate", -kInf, kInf);
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
      command.velocity = u * wheel_velocity_scale_[i];
      command.kp_scale = config_.wheel_kp_scale;
      command.kd_scale = config_.wheel_kd_scale;
    } else {
      command.position =
          limits.lower + 0.5 * (config_.leg_action_scale * u + 1.0) * (limits.upper - limits.lower);
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

double ServosTaskEnv::normalized_action_magnitude(std::span<const float> normalized) {
  double sum = 0.0;
  for (const float u : normalized) sum += std::abs(u);
  return normalized.empty() ? 0.0 : sum / static_cast<double>(normalized.size());
}

void ServosTaskEnv::write_observation(const Observation& full, std::span<float> observation) const {
  if (observation.size() != observation_space_.size()) {
    throw std::invalid_argument("ServosTaskEnv: observation buffer has " +
                                std::to_string(observation.size()) + " components, expected " +
                                std::to_string(observation_space_.size()));
  }
  for (std::size_t i = 0; i < kNumServos; ++i) {
    observation[2 * i] = static_cast<float>(full.servo[i].position);
    observation[2 * i + 1] = static_cast<float>(full.servo[i].velocity);
  }
  if (config_.observe_pitch) {
    observation[2 * kNumServos] = static_cast<float>(full.base_orientation.pitch);
    observation[2 * kNumServos + 1] =
        static_cast<float>(full.base_orientation.angular_velocity.y());
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
  const double magnitude =
      config_.action_magnitude == ServosTaskConfig::ActionMagnitude::kNormalized
          ? normalized_action_magnitude(clamped_)
          : action_magnitude(servo_action_);
  return task_.evaluate(full, magnitude);
}

void ServosTaskConfig::declare_options(OptionTable& table) {
  termination.declare_options(table);
  reward.declare_options(table);
  table.add_choice("observe_pitch", &observe_pitch, {{"false", false}, {"true", true}},
                   "append the base pitch and pitch rate (the IMU's) to the 12 joint components");
  table.add_choice(
      "action_magnitude", &action_magnitude,
      {{"servo", ActionMagnitude::kServo}, {"normalized", ActionMagnitude::kNormalized}},
      "|a| of the reward: wheel rad/s + leg rad (seed) or mean |u| of the action");
  table.add_real("max_wheel_velocity", &max_wheel_velocity, 0.0, kOptionHuge,
                 "wheel velocity at action 1 [rad/s], 0 for the velocity limit");
  table.add_real("leg_action_scale", &leg_action_scale, 1e-3, 1.0,
                 "fraction of each leg joint's range spanned by the action");
}

}  // namespace upkie_rl
