#pragma once
/// @file
/// VelocityBalancerGains: the numbers of the velocity task's classical balance law.

#include <array>
#include <cstddef>

namespace upkie_rl {

/// The numbers of the law (see ForwardBalanceLaw and VelocityBalancer);
/// envs/controllers/velocity_balancer_design.hpp designs them on the environment.
struct VelocityBalancerGains {
  /// k of u = u_ss + k·[θ - θ_ss, θ̇, v̂ - v_ref, e] in the order pitch [m/s/rad], pitch
  /// rate [m/s/(rad/s)], velocity error [1], integral of the velocity error [1/s].
  std::array<double, 4> feedback{};
  double pitch_offset = 0.0;              ///< θ_ss at rest [rad] (the centre of mass's offset).
  double pitch_per_velocity = 0.0;        ///< dθ_ss/dv_ref [rad/(m/s)] (rolling losses).
  double command_offset = 0.0;            ///< u_ss at rest [m/s].
  double command_per_velocity = 1.0;      ///< du_ss/dv_ref [1].
  double pitch_per_acceleration = 0.0;    ///< dθ_ss/da_ref [rad/(m/s²)] (the lean).
  double command_per_acceleration = 0.0;  ///< du_ss/da_ref [s].

  /// How many numbers the `balancer:` spec gives: the members in order.
  static constexpr std::size_t kNumValues = 10;
  /// A spec of the first kNumLegacyValues members leaves the acceleration feedforward at 0.
  static constexpr std::size_t kNumLegacyValues = 8;
};

}  // namespace upkie_rl
