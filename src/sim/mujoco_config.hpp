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
  /// The wheels' velocity-loop damping integrated implicitly, as MuJoCo's Euler integrator
  /// does joint damping (the rest of the servo law stays explicit). Evaluated explicitly
  /// once per 1 ms physics step, the damping kd·kd_scale against the wheel's own spin
  /// inertia (kd·dt/I ≈ 6, above the explicit limit of 2) makes the wheel's speed chatter
  /// at its torque limit while the tire slips a little: 9.7 rad/s of standard deviation
  /// standing still, 1.8 rad/s implicit. Off by default: the tasks trained before keep
  /// their physics; the velocity task turns it on.
  bool implicit_wheel_damping = false;

  /// @throws std::invalid_argument naming the first setting out of its domain.
  void validate() const;
};

}  // namespace upkie_rl
