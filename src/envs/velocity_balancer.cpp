#include "envs/velocity_balancer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "envs/velocity_env.hpp"

namespace upkie_rl {

namespace {

// Components of the velocity task's observation (VelocityTask).
constexpr std::size_t kLeftWheelVelocity = 4;
constexpr std::size_t kRightWheelVelocity = 5;
constexpr std::size_t kGravityX = 6;
constexpr std::size_t kGravityZ = 8;
constexpr std::size_t kGyroY = 10;
constexpr double kMaxPositionError = 5.0;  // [m]
constexpr double kMaxAcceleration = 1.0;   // of the velocity reference [m/s²]

const VelocityEnv& velocity_env(const Env& env) {
  const VelocityEnv* velocity = find_velocity_env(env);
  if (velocity == nullptr) {
    throw std::invalid_argument(
        "velocity balancer: the environment is not a velocity task (Upkie-*-Velocity)");
  }
  return *velocity;
}

}  // namespace

VelocityBalancer::VelocityBalancer(const Env& env, const std::array<float, 4>& gains)
    : gains_(gains) {
  const VelocityEnv& velocity = velocity_env(env);
  const RobotModel& model = velocity.servos().model();
  wheel_radius_ = model.wheel_radius();
  yaw_factor_ = 0.5 * model.track() / wheel_radius_;
  wheel_velocity_scale_ = velocity.task().config().wheel_velocity_scale;
  timestep_ = env.timestep();
}

void VelocityBalancer::act(std::span<const float> observation, std::span<float> action) {
  // The reference ramps toward the command: a step of the wheel speed would kick the body
  // over (it tilts backward when the wheels leap forward).
  const double commanded = observation[VelocityTask::kCommandIndex];
  const double max_change = kMaxAcceleration * timestep_;
  reference_velocity_ += std::clamp(commanded - reference_velocity_, -max_change, max_change);
  const double forward_command = reference_velocity_;
  const double yaw_command = observation[VelocityTask::kCommandIndex + 1];
  const double pitch = std::atan2(observation[kGravityX], -observation[kGravityZ]);
  const double pitch_rate = observation[kGyroY];
  const double ground_velocity =
      0.5 * wheel_radius_ * (observation[kLeftWheelVelocity] - observation[kRightWheelVelocity]);
  const double velocity_error = ground_velocity - forward_command;
  // Bounded, so that a command the robot cannot follow does not wind the integral up.
  position_error_ = std::clamp(position_error_ + velocity_error * timestep_, -kMaxPositionError,
                               kMaxPositionError);
  const double command = forward_command + gains_[0] * pitch + gains_[1] * position_error_ +
                         gains_[2] * pitch_rate + gains_[3] * velocity_error;
  // Joint convention: the left wheel forward and the right one backward turn clockwise.
  const double turn = -yaw_factor_ * yaw_command;
  std::fill(action.begin(), action.end(), 0.0f);
  const auto normalized = [this](double wheel_velocity) {
    return static_cast<float>(std::clamp(wheel_velocity / wheel_velocity_scale_, -1.0, 1.0));
  };
  action[kLeftWheel] = normalized(command / wheel_radius_ + turn);
  action[kRightWheel] = normalized(-command / wheel_radius_ + turn);
}

}  // namespace upkie_rl
