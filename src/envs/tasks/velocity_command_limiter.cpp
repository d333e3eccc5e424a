#include "envs/tasks/velocity_command_limiter.hpp"

#include <algorithm>
#include <cmath>

namespace upkie_rl {

namespace {

/// `current` moved toward `target` by at most `max_rate`·dt, or `target` if max_rate is 0.
double approach(double current, double target, double max_rate, double dt) {
  if (max_rate <= 0.0) return target;
  const double max_change = max_rate * dt;
  if (std::abs(target - current) <= max_change) return target;  // exactly, not c + (t - c)
  return current + std::clamp(target - current, -max_change, max_change);
}

}  // namespace

void VelocityCommandLimiter::start(const VelocityCommand& target, double rest_height) {
  command_.forward_velocity = max_acceleration_ > 0.0 ? 0.0 : target.forward_velocity;
  command_.yaw_rate = max_yaw_acceleration_ > 0.0 ? 0.0 : target.yaw_rate;
  command_.height = max_height_velocity_ > 0.0 ? rest_height : target.height;
}

VelocityCommand VelocityCommandLimiter::rate(const VelocityCommand& target, double dt) const {
  const auto component_rate = [dt](double current, double goal, double max_rate) {
    return max_rate > 0.0 ? (approach(current, goal, max_rate, dt) - current) / dt : 0.0;
  };
  VelocityCommand rates;
  rates.forward_velocity =
      component_rate(command_.forward_velocity, target.forward_velocity, max_acceleration_);
  rates.yaw_rate = component_rate(command_.yaw_rate, target.yaw_rate, max_yaw_acceleration_);
  rates.height = component_rate(command_.height, target.height, max_height_velocity_);
  return rates;
}

const VelocityCommand& VelocityCommandLimiter::advance(const VelocityCommand& target, double dt) {
  command_.forward_velocity =
      approach(command_.forward_velocity, target.forward_velocity, max_acceleration_, dt);
  command_.yaw_rate = approach(command_.yaw_rate, target.yaw_rate, max_yaw_acceleration_, dt);
  command_.height = approach(command_.height, target.height, max_height_velocity_, dt);
  return command_;
}

}  // namespace upkie_rl
