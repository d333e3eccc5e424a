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
  /// Contact dimensionality of the tires: 3 is sliding friction only; 6 adds MuJoCo's
  /// torsional and rolling friction (the URDF's rolling friction, as Bullet has). With 6,
  /// MuJoCo's rolling friction is a constraint in the same friction cone as the sliding
  /// one: a rolling tire is at the cone's edge, so it slides as well. A driven tire then
  /// slips forward by about a third (the wheels turn 1.45 times as fast as they roll: an
  /// effective radius of 0.035 m for 0.050 m at 0.35 m/s; elliptic cones: 0.031 m; Bullet,
  /// whose rolling friction is a separate constraint: 0.051 m). So the robot's tires are 3
  /// (0.050 m), for every task and for the simulation spine: one robot, one physics; 6
  /// remains for comparisons (bench/sim_bench.cpp).
  int tire_condim = 3;
  /// The wheels' velocity-loop damping integrated implicitly, as MuJoCo's Euler integrator
  /// does joint damping (the rest of the servo law stays explicit). Evaluated explicitly
  /// once per 1 ms physics step, the damping kd·kd_scale against the wheel's own spin
  /// inertia (kd·dt/I ≈ 3.8, above the explicit limit of 2) makes the wheel's speed chatter
  /// at its torque limit while the tire slips a little: 9.7 rad/s of standard deviation
  /// standing still, 1.8 rad/s implicit. On for the robot, every task and the spine alike;
  /// off only to measure the difference (tests/sim/mujoco_wheel_damping_test.cpp).
  bool implicit_wheel_damping = true;
  /// With tire_condim 3, the tires' rolling resistance as a torque of its own on each
  /// wheel against its rolling, up to the URDF's rolling_friction [m] × the tire's normal
  /// force, outside the friction cone, as Bullet's separate rolling friction constraint:
  /// the tires neither roll freely (as with 3 alone) nor slip (as with 6). On for the
  /// robot, so that both engines carry the one description's tires: without it a limp robot
  /// released upright rolled upright for 5 s instead of falling in about 1 s, and the fixed
  /// pendulum law of tests/sim/physics_behaviour_test.cpp drifted and fell after 6 s where
  /// it holds 0.015 rad on Bullet (0.014 rad with it; tests/sim/mujoco_tire_test.cpp).
  bool tire_rolling_resistance = true;

  /// @throws std::invalid_argument naming the first setting out of its domain.
  void validate() const;
};

}  // namespace upkie_rl
