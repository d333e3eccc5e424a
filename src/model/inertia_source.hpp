#pragma once
/// @file
/// Where link inertias come from.

namespace upkie_rl {

/// Where link inertias come from.
enum class InertiaSource {
  /// Bullet's rule: box formula on the bounding box of the link's collision shapes, with
  /// cylinders as 32-gon hulls inflated by their margin (what PyBullet simulates; default).
  kBulletBoxRule,
  /// The tensors written in the URDF.
  kUrdf,
};

}  // namespace upkie_rl
