#pragma once
/// @file
/// Randomisation of the initial state at each reset (public Upkie's InitRandomization).

#include <cstdint>
#include <random>

#include "base/option_table.hpp"
#include "sim/random_draws.hpp"
#include "sim/reset_state.hpp"

namespace upkie_rl {

/// Half-widths of uniform distributions around the default initial state. All zero (the
/// default) gives the deterministic reset: base at (0, 0, 0.6), upright, at rest.
struct InitRandomization {
  double roll = 0.0;   ///< Base roll drawn in [-roll, roll] [rad].
  double pitch = 0.0;  ///< Base pitch drawn in [-pitch, pitch] [rad] (ZYX, yaw 0).
  double x = 0.0;      ///< Base x position offset in [-x, x] [m].
  double z = 0.0;      ///< Base height raised by [0, z] [m] (never lowered).
  double omega_x =
      0.0;  ///< Base angular velocity about x in [-omega_x, omega_x], base frame [rad/s].
  double omega_y = 0.0;  ///< Same about y [rad/s].
  double v_x = 0.0;      ///< Base linear velocity along x in [-v_x, v_x], world frame [m/s].
  double v_y = 0.0;      ///< Same along y [m/s].
  double v_z = 0.0;      ///< Same along z [m/s].

  /// These ranges multiplied by `scale` (a curriculum's ramp).
  InitRandomization scaled(double scale) const {
    return {scale * roll,    scale * pitch, scale * x,   scale * z,  scale * omega_x,
            scale * omega_y, scale * v_x,   scale * v_y, scale * v_z};
  }

  /// Draws an initial state. Always consumes the same number of draws, so the sequence of
  /// states from a seed does not depend on which ranges are zero.
  ResetState sample(std::mt19937_64& generator) const;

  /// Declares the options init_rand_roll ... init_rand_v_z.
  void declare_options(OptionTable& table);
};

}  // namespace upkie_rl
