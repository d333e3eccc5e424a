#include "sim/mujoco_config.hpp"

#include <stdexcept>
#include <string>

namespace upkie_rl {

void MujocoConfig::validate() const {
  PhysicsConfig::validate("MujocoConfig");
  if (solver_iterations < 1) {
    throw std::invalid_argument("MujocoConfig: solver_iterations must be at least 1, got " +
                                std::to_string(solver_iterations));
  }
  if (tire_condim != 3 && tire_condim != 6) {
    throw std::invalid_argument("MujocoConfig: tire_condim must be 3 or 6, got " +
                                std::to_string(tire_condim));
  }
}

}  // namespace upkie_rl
