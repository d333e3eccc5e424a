#pragma once
/// @file
/// Options that several environment kinds declare: one name, range and help each, so that
/// the pendulum and the gyropod (say) cannot come to mean different things by the same name.

#include <stdexcept>
#include <string>

#include "base/option_table.hpp"
#include "envs/kinds/servos_env.hpp"

namespace upkie_rl {

/// Largest value of the options that accept any non-negative magnitude.
inline constexpr double kOptionHuge = 1e9;

/// Terminate on |pitch| above it (BalanceTermination, GyropodConfig).
inline constexpr RealOptionSpec kFallPitchOption{"fall_pitch", 0.0, kOptionHuge,
                                                 "terminate when |pitch| exceeds it [rad]"};
/// Bound of the commanded ground velocity (PendulumConfig, GyropodConfig).
inline constexpr RealOptionSpec kMaxGroundVelocityOption{"max_ground_velocity", 1e-6, kOptionHuge,
                                                         "action bound a_max [m/s]"};
/// Gain scales of the legs held at their default pose (PendulumConfig, GyropodConfig).
inline constexpr RealOptionSpec kLegGainScaleOption{"leg_gain_scale", 0.0, ServosEnv::kMaxGainScale,
                                                    "gain scales of the held legs"};

/// A settings struct's validate(): throws std::invalid_argument with the problem its
/// rule found (the same text the option table reports), if any.
inline void throw_problem(const std::string& problem) {
  if (!problem.empty()) throw std::invalid_argument(problem);
}

}  // namespace upkie_rl
