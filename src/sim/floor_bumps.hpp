#pragma once
/// @file
/// FloorBumps: door sills and cable bumps lying across the floor, a fixed part of a
/// simulated world (Bullet and MuJoCo build them with the world, not per episode).

#include <string>
#include <vector>

#include "model/option_table.hpp"

namespace upkie_rl {

/// Height of a bump above the floor, 0 for none (option bump_height) [m].
inline constexpr RealOptionSpec kBumpHeightOption{
    "bump_height", 0.0, 0.05, "height of the bumps across the floor [m], 0 for none"};
/// Distance between successive bumps along x (option bump_spacing) [m].
inline constexpr RealOptionSpec kBumpSpacingOption{"bump_spacing", 0.2, 10.0,
                                                   "distance between successive bumps along x [m]"};
/// Extent of a bump along x, the direction of travel (option bump_width) [m].
inline constexpr RealOptionSpec kBumpWidthOption{
    "bump_width", 0.005, 0.5, "extent of a bump along x [m], at most half bump_spacing"};

/// Bumps lie at x = ±spacing, ±2 spacing, ... up to this distance from the origin [m].
inline constexpr double kBumpFieldHalfLength = 20.0;
/// Length of a bump along y, centred on y = 0 [m]: as far sideways as the field reaches.
inline constexpr double kBumpLength = 2.0 * kBumpFieldHalfLength;
/// Depth of a bump below the floor's surface [m]. The box reaches into the floor so that
/// even a millimetre-high bump is a box thicker than Bullet's 1 mm collision margin (the
/// floor is static: the part below it never touches anything).
inline constexpr double kBumpFooting = 0.01;

/// Boxes lying along y across the floor, at x = k·spacing for k = ±1, ±2, ... within
/// kBumpFieldHalfLength: perpendicular to the heading of a robot reset at the origin with
/// yaw 0 (the environments' resets), which starts between the bumps at ±spacing. They have
/// the floor's friction, and a robot part touching one touches the floor (floor_contact).
/// The default, height 0, adds nothing to the world: every trajectory is bit for bit the
/// flat floor's.
struct FloorBumps {
  double height = 0.0;   ///< Above the floor [m]; 0 for no bumps.
  double spacing = 1.0;  ///< Between the centres of successive bumps [m].
  double width = 0.03;   ///< Along x [m].

  bool enabled() const { return height > 0.0; }

  /// The x of every bump's centre, increasing, none at 0 [m]; empty when disabled.
  std::vector<double> centres() const;

  /// Declares bump_height, bump_spacing and bump_width in `table`, and problem() as their
  /// rule.
  void declare_options(OptionTable& table);

  /// A width above half the spacing (bumps nearly touching, no room to start between
  /// them), named; "" if none. The ranges are the option table's (or validate's).
  std::string problem() const;
  /// @throws std::invalid_argument naming the option out of its declared range, or
  ///         problem(); `prefix` starts the message (e.g. "BulletConfig: ").
  void validate(const std::string& prefix = "") const;
};

}  // namespace upkie_rl
