#pragma once
/// @file
/// When a tire touches the floor, the same for every physics backend.

namespace upkie_rl {

/// A tire closer to the floor than this counts as touching it [m]: Bullet's contact points
/// and MuJoCo's contacts (whose tires detect contacts within this margin) are compared
/// with it for Observation::floor_contact.
inline constexpr double kTireContactDistance = 1e-3;

}  // namespace upkie_rl
