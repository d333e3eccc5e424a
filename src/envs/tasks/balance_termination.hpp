#pragma once
/// @file
/// The seed's termination conditions (section 1.5), shared by the pendulum and servos task.

#include <cmath>

#include "base/option_table.hpp"

namespace upkie_rl {

/// Thresholds of the termination conditions.
struct BalanceTermination {
  double fall_pitch = 1.0;             ///< |θ| above it: fall [rad].
  double max_position_drift = 5.0;     ///< |p - p0| above it: drift [m].
  double max_angular_velocity = 10.0;  ///< |θ̇| above it [rad/s].
  double max_linear_velocity = 2.0;    ///< |ṗ| above it [m/s].

  /// Declares the options fall_pitch, max_position_drift, max_angular_velocity and
  /// max_linear_velocity (balance_options.cpp).
  void declare_options(OptionTable& table);

  /// Why an episode ended, in the order the conditions are checked.
  enum class Reason { kNone = 0, kFall, kPositionDrift, kAngularVelocity, kLinearVelocity };

  /// The first condition met, checked in the seed's order: fall, drift, angular velocity,
  /// linear velocity.
  Reason check(double pitch, double position_drift, double pitch_rate,
               double ground_velocity) const {
    if (std::abs(pitch) > fall_pitch) return Reason::kFall;
    if (std::abs(position_drift) > max_position_drift) return Reason::kPositionDrift;
    if (std::abs(pitch_rate) > max_angular_velocity) return Reason::kAngularVelocity;
    if (std::abs(ground_velocity) > max_linear_velocity) return Reason::kLinearVelocity;
    return Reason::kNone;
  }
};

/// "fall", "position_drift", "angular_velocity", "linear_velocity" or "none".
constexpr const char* to_string(BalanceTermination::Reason reason) {
  switch (reason) {
    case BalanceTermination::Reason::kFall:
      return "fall";
    case BalanceTermination::Reason::kPositionDrift:
      return "position_drift";
    case BalanceTermination::Reason::kAngularVelocity:
      return "angular_velocity";
    case BalanceTermination::Reason::kLinearVelocity:
      return "linear_velocity";
    default:
      return "none";
  }
}

}  // namespace upkie_rl
