#pragma once
/// @file
/// Settings every physics backend shares (Bullet, MuJoCo).

#include "model/inertia_source.hpp"
#include "sim/floor_bumps.hpp"
#include "sim/servo_law.hpp"

namespace upkie_rl {

/// What a physics backend is built with; fixed after construction (what changes during a
/// run, such as the servo gains a spine Start sets, lives in the simulation's state).
/// Defaults reproduce the reference PyBullet setup: 1 kHz physics, 200 Hz agent.
struct PhysicsConfig {
  double physics_timestep = 1e-3;  ///< Duration of one physics step [s].
  int nb_substeps = 5;             ///< Physics steps per agent step.
  InertiaSource inertia_source = InertiaSource::kBulletBoxRule;
  bool floor = true;         ///< A ground plane at z = 0.
  FloorBumps bumps{};        ///< Bumps across the floor (none by default); need the floor.
  double gravity = 9.81;     ///< [m/s^2], along -z.
  ServoGains servo_gains{};  ///< Servo law gains at construction.

  /// Duration of one agent step [s].
  double agent_timestep() const { return physics_timestep * nb_substeps; }

  /// @throws std::invalid_argument naming the first setting out of its domain.
  void validate(const char* backend) const;
};

}  // namespace upkie_rl
