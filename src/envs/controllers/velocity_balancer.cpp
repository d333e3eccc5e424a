#include "envs/controllers/velocity_balancer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "envs/kinds/velocity_env.hpp"

namespace upkie_rl {

namespace {

// Components of the velocity task's observation (VelocityTask).
constexpr std::size_t kLeftWheelVelocity = 4;
constexpr std::size_t kRightWheelVelocity = 5;
constexpr std::size_t kGravityX = 6;
constexpr std::size_t kGravityZ = 8;
constexpr std::size_t kGyroY = 10;
constexpr std::size_t kGyroZ = 11;
constexpr double kMaxYawRateIntegral = 1.0;  // [rad]

const VelocityEnv& velocity_env(const Env& env) {
  const VelocityEnv* velocity = find_velocity_env(env);
  if (velocity == nullptr) {
    throw std::invalid_argument(
        "velocity balancer: the environment is not a velocity task (Upkie-*-Velocity)");
  }
  return *velocity;
}

}  // namespace

double velocity_task_pitch(std::span<const float> observation) {
  return std::atan2(observation[kGravityX], -observation[kGravityZ]);
}

double velocity_task_pitch_rate(std::span<const float> observation) { return observation[kGyroY]; }

VelocityBalancer::VelocityBalancer(const Env& env, const VelocityBalancerGains& gains)
    : forward_(forward_law(gains, env.timestep())), legs_(velocity_env(env).servos().model()) {
  const VelocityEnv& velocity = velocity_env(env);
  const VelocityTaskConfig& task = velocity.task().config();
  if (task.relative_wheel_action || task.wheel_command_feedforward) {
    throw std::invalid_argument(
        "the velocity balancer computes whole wheel velocity targets: it needs "
        "relative_wheel_action and wheel_command_feedforward false");
  }
  const RobotModel& model = velocity.servos().model();
  wheels_ = model.wheel_geometry();
  wheel_velocity_scale_ = velocity.task().config().wheel_velocity_scale;
  leg_action_scale_ = velocity.task().config().leg_action_scale;
  leg_action_about_crouch_ = velocity.task().config().leg_action_about_crouch;
  height_command_ = velocity.task().height_command();
  timestep_ = env.timestep();
  touchdown_steps_ = static_cast<int>(std::lround(kTouchdownTime / timestep_));
}

ForwardBalanceLaw VelocityBalancer::forward_law(const VelocityBalancerGains& gains,
                                                double timestep) {
  return {gains, timestep,
          filter_gain_at_rate(kVelocityFilterGain, kFilterDesignTimestep, timestep),
          filter_gain_at_rate(kAccelerationFilterGain, kFilterDesignTimestep, timestep)};
}

void VelocityBalancer::reset() {
  steps_since_reset_ = 0;
  forward_.reset();
  yaw_rate_error_integral_ = 0.0;
}

void VelocityBalancer::act(std::span<const float> observation, std::span<float> action) {
  if (steps_since_reset_ < touchdown_steps_) {
    ++steps_since_reset_;
    std::fill(action.begin(), action.end(), 0.0f);
    if (height_command_) write_leg_actions(observation, {}, action);  // straight legs
    return;
  }
  const double odometry =
      wheels_.forward_motion(observation[kLeftWheelVelocity], observation[kRightWheelVelocity]);
  const double ground_velocity =
      forward_.ground_velocity({.command = observation[VelocityTask::kCommandIndex],
                                .pitch = velocity_task_pitch(observation),
                                .pitch_rate = velocity_task_pitch_rate(observation),
                                .odometry_velocity = odometry});

  // Yaw: the differential wheel speed of the command, corrected by a PI loop on the
  // gyroscope (the tires slip a little when turning).
  const double yaw_command = observation[VelocityTask::kCommandIndex + 1];
  const double yaw_error = yaw_command - observation[kGyroZ];
  yaw_rate_error_integral_ = std::clamp(yaw_rate_error_integral_ + yaw_error * timestep_,
                                        -kMaxYawRateIntegral, kMaxYawRateIntegral);
  const double yaw_rate =
      yaw_command + kYawRateGain * yaw_error + kYawRateIntegralGain * yaw_rate_error_integral_;
  std::fill(action.begin(), action.end(), 0.0f);
  const auto normalized = [this](double wheel_velocity) {
    return static_cast<float>(std::clamp(wheel_velocity / wheel_velocity_scale_, -1.0, 1.0));
  };
  const WheelVelocities wheels = wheels_.velocities(ground_velocity, yaw_rate);
  action[kLeftWheel] = normalized(wheels.left);
  action[kRightWheel] = normalized(wheels.right);
  if (height_command_) crouch(observation, action);
}

double VelocityBalancer::commanded_height(std::span<const float> observation) {
  if (observation.size() <= VelocityTask::kHeightCommandIndex) {
    throw std::invalid_argument("velocity balancer: an observation of " +
                                std::to_string(observation.size()) +
                                " components has no height command, which its env has");
  }
  return observation[VelocityTask::kHeightCommandIndex];
}

void VelocityBalancer::crouch(std::span<const float> observation, std::span<float> action) const {
  // Leaning forward tilts the crouched shins further from the vertical: the crouch is
  // limited so that the ankles' boxes clear the floor (kCrouchShinTilt).
  const double lean = std::max(0.0, velocity_task_pitch(observation));
  const double lowest =
      legs_.height_at_shin_tilt(std::max(0.0, kCrouchShinTilt - kCrouchLeanGain * lean));
  const double height = std::max(commanded_height(observation), lowest);
  write_leg_actions(observation, legs_.crouch_pose(height).leg_angles(), action);
}

void VelocityBalancer::write_leg_actions(std::span<const float> observation,
                                         const std::array<double, 4>& angles,
                                         std::span<float> action) const {
  // The task's action origin (leg_action_about_crouch: the commanded crouch) is taken off,
  // so that the servo targets are the same either way.
  const std::array<double, 4> origin =
      leg_action_about_crouch_
          ? leg_action_origin_angles(legs_, true, commanded_height(observation))
          : std::array<double, 4>{};
  for (std::size_t k = 0; k < VelocityTask::kLegJoints.size(); ++k) {
    action[VelocityTask::kLegJoints[k]] =
        static_cast<float>(std::clamp((angles[k] - origin[k]) / leg_action_scale_, -1.0, 1.0));
  }
}

}  // namespace upkie_rl
