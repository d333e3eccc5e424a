#pragma once
/// @file
/// Settings of the Bullet simulation backend.

#include "sim/physics_config.hpp"

namespace upkie_rl {

/// Settings of BulletSimulation. Defaults reproduce the reference PyBullet setup.
struct BulletConfig : PhysicsConfig {
  /// Merge links joined by fixed joints into one rigid body (same mass, COM and inertia;
  /// about 6x fewer bodies for Featherstone to step).
  bool merge_fixed_links = true;
};

}  // namespace upkie_rl
