#include "sim/physics_simulation.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace upkie_rl {

void PhysicsSimulation::set_servo_gains(const ServoGains& gains) {
  if (!is_valid_servo_gain(gains.kp) || !is_valid_servo_gain(gains.kd)) {
    throw std::invalid_argument("servo gains must be finite and non-negative, got kp " +
                                std::to_string(gains.kp) + " and kd " + std::to_string(gains.kd));
  }
  servo_gains_ = gains;
}

double PhysicsSimulation::joint_torque(const ServoCommand& command, bool braked, double position,
                                       double velocity, double effort) const {
  if (braked) return std::clamp(-servo_gains_.kd * velocity, -kBrakeTorque, kBrakeTorque);
  return servo_torque(command, position, velocity, servo_gains_, effort);
}

}  // namespace upkie_rl
