#pragma once
/// @file
/// FloorBumps: door sills and cable bumps lying across the floor, a fixed part of a
/// simulated world (Bullet and MuJoCo build them with the world, not per episode).

#include <array>
#include <string>
#include <vector>

#include "base/option_table.hpp"

namespace upkie_rl {

/// Height of a bump above the floor, 0 for none (option bump_height) [m].
inline constexpr RealOptionSpec kBumpHeightOption{
    "bump_height", 0.0, 0.05, "height of the bumps across the floor [m], 0 for none"};
/// Distance between successive bumps along x (option bump_spacing) [m].
inline constexpr RealOptionSpec kBumpSpacingOption{"bump_spacing", 0.2, 10.0,
                                                   "distance between successive bumps along x [m]"};
/// Extent of a bump's flat top along x, the direction of travel (option bump_width) [m].
inline constexpr RealOptionSpec kBumpWidthOption{
    "bump_width", 0.005, 0.5,
    "extent of a bump's flat top along x [m]; with its ramps, at most half bump_spacing"};

/// Horizontal run of each edge of a bump per unit of its rise (option bump_ramp): 0 for
/// square edges, 2 for a 1:2 bevel (cable covers and accessible door sills are bevelled).
inline constexpr RealOptionSpec kBumpRampOption{
    "bump_ramp", 0.0, 10.0,
    "horizontal run of each edge of a bump per unit of rise, 0 for square edges, 2 for 1:2"};

/// Bumps lie at x = ±spacing, ±2 spacing, ... up to this distance from the origin [m].
inline constexpr double kBumpFieldHalfLength = 20.0;
/// Length of a bump along y, centred on y = 0 [m]: as far sideways as the field reaches.
inline constexpr double kBumpLength = 2.0 * kBumpFieldHalfLength;
/// Depth of a bump below the floor's surface [m]. The box reaches into the floor so that
/// even a millimetre-high bump is a box thicker than Bullet's 1 mm collision margin (the
/// floor is static: the part below it never touches anything).
inline constexpr double kBumpFooting = 0.01;

/// Prisms lying along y across the floor, at x = k·spacing for k = ±1, ±2, ... within
/// kBumpFieldHalfLength: perpendicular to the heading of a robot reset at the origin with
/// yaw 0 (the environments' resets), which starts between the bumps at ±spacing. Square
/// boxes by default; with a ramp, trapezoids in section: a flat top of `width` and, on each
/// side, a slope down to the floor over ramp_run() along x. They have the floor's
/// friction, and a robot part touching one touches the floor (floor_contact).
/// The default, height 0, adds nothing to the world: every trajectory is bit for bit the
/// flat floor's.
struct FloorBumps {
  double height = 0.0;   ///< Above the floor [m]; 0 for no bumps.
  double spacing = 1.0;  ///< Between the centres of successive bumps [m].
  double width = 0.03;   ///< Of the flat top, along x [m].
  double ramp = 0.0;     ///< Run of each edge per unit of rise; 0 for square edges.

  bool enabled() const { return height > 0.0; }
  /// Whether the edges slope (a trapezoidal section) rather than stand square.
  bool ramped() const { return ramp > 0.0; }
  /// Length along x of each edge's slope, from the floor to the top [m].
  double ramp_run() const { return ramp * height; }
  /// Extent along x of a bump on the floor: its top and both slopes [m].
  double footprint() const { return width + 2.0 * ramp_run(); }

  /// Height of the bumps' surface above the floor at `x`, 0 between them [m].
  double surface_height(double x) const;

  /// Corners (x, z) of a ramped bump's section, centred on x = 0 with the floor at z = 0:
  /// top right, bottom right, bottom left, top left, the bottom kBumpFooting below the
  /// floor. Each face moves in by `inset` [m] (Bullet's collision margin, which its convex
  /// hulls add around their points), so that the shape touched is the trapezoid.
  std::array<std::array<double, 2>, 4> ramped_section(double inset = 0.0) const;

  /// The x of every bump's centre, increasing, none at 0 [m]; empty when disabled.
  std::vector<double> centres() const;

  /// Declares bump_height, bump_spacing, bump_width and bump_ramp in `table`, and problem()
  /// as their rule.
  void declare_options(OptionTable& table);

  /// A footprint (top and slopes) above half the spacing (bumps nearly touching, no room
  /// to start between them), naming the options; "" if none. The ranges are the option
  /// table's (or validate's).
  std::string problem() const;
  /// @throws std::invalid_argument naming the option out of its declared range, or
  ///         problem(); `prefix` starts the message (e.g. "BulletConfig: ").
  void validate(const std::string& prefix = "") const;

 private:
  /// Bumps on each side of the origin, up to kBumpFieldHalfLength; 0 when disabled.
  int bumps_per_side() const;
};

}  // namespace upkie_rl
