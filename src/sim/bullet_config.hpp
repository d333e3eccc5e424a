#pragma once
/// @file
/// Settings of the Bullet simulation backend.

#include "model/inertia_source.hpp"

namespace upkie_rl {

/// Settings of BulletSimulation. Defaults reproduce the reference PyBullet setup.
struct BulletConfig {
  double physics_timestep = 1e-3;  ///< Duration of one physics step [s].
  int nb_substeps = 5;             ///< Physics steps per agent step (1000*dt at 1 kHz).
  InertiaSource inertia_source = InertiaSource::kBulletBoxRule;
  bool floor = true;      ///< A fixed ground box with its top face at z = 0.
  double gravity = 9.81;  ///< [m/s^2], along -z.
  double kp = 20.0;       ///< Servo position gain [N.m/rad].
  double kd = 1.0;        ///< Servo velocity gain [N.m.s/rad].
  /// Merge links joined by fixed joints into one rigid body (same mass, COM and inertia;
  /// about 6x fewer bodies for Featherstone to step).
  bool merge_fixed_links = true;
};

}  // namespace upkie_rl
