#pragma once
/// @file
/// Settings of the MuJoCo simulation backend.

#include "sim/physics_config.hpp"

namespace upkie_rl {

/// Settings of MujocoSimulation. The physics rate and servo law are those of Bullet
/// (PhysicsConfig defaults: 1 kHz, 5 physics steps per 200 Hz agent step), so that a
/// policy sees the same servo dynamics on both engines.
struct MujocoConfig : PhysicsConfig {
  /// Iterations of MuJoCo's Newton constraint solver (it converges in 2-4 on Upkie; the
  /// cap only matters in hard impacts).
  int solver_iterations = 20;
  /// Contact dimensionality of the tires: 6 adds MuJoCo's torsional and rolling friction
  /// (the URDF's rolling friction, as Bullet has); 3 is sliding friction only (cheaper).
  int tire_condim = 6;

  /// @throws std::invalid_argument naming the first setting out of its domain.
  void validate() const;
};

}  // namespace upkie_rl
