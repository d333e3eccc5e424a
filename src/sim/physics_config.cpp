#include "sim/physics_config.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace upkie_rl {

void PhysicsConfig::validate(const char* backend) const {
  const std::string prefix = std::string(backend) + ": ";
  if (!(physics_timestep > 0.0) || !std::isfinite(physics_timestep)) {
    throw std::invalid_argument(prefix + "physics_timestep must be positive, got " +
                                std::to_string(physics_timestep));
  }
  if (nb_substeps < 1) {
    throw std::invalid_argument(prefix + "nb_substeps must be at least 1, got " +
                                std::to_string(nb_substeps));
  }
  if (!std::isfinite(gravity)) throw std::invalid_argument(prefix + "gravity must be finite");
  if (!is_valid_servo_gain(servo_gains.kp) || !is_valid_servo_gain(servo_gains.kd)) {
    throw std::invalid_argument(prefix + "servo gains must be finite and non-negative");
  }
  bumps.validate(prefix);
  if (bumps.enabled() && !floor) {
    throw std::invalid_argument(prefix + kBumpHeightOption.name + " needs the floor");
  }
}

}  // namespace upkie_rl
