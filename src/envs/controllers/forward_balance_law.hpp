#pragma once
/// @file
/// ForwardBalanceLaw: the ground velocity that balances a wheeled inverted pendulum while it
/// follows a forward velocity command. The wheel law of VelocityBalancer, apart from its
/// observation layout, so that other drivers (the excitation logs of identification) balance
/// the robot the same way.

#include "envs/controllers/velocity_balancer_gains.hpp"

namespace upkie_rl {

/// What the law reads at each step.
struct ForwardBalanceInputs {
  double command = 0.0;            ///< v* [m/s]
  double pitch = 0.0;              ///< θ [rad], positive leaning forward
  double pitch_rate = 0.0;         ///< θ̇ [rad/s]
  double odometry_velocity = 0.0;  ///< The wheels' ground velocity, unfiltered [m/s]
};

/// With v̂ the odometry velocity low-pass filtered, v_ref a reference ramping toward v* at
/// most kMaxAcceleration, a_ref its acceleration low-pass filtered and e the integral of
/// v̂ - v_ref (bounded to ±kMaxPositionError):
///
///   u = u_ss + k·[θ - θ_ss, θ̇, v̂ - v_ref, e],
///   θ_ss = pitch_offset + pitch_per_velocity·v_ref + pitch_per_acceleration·a_ref,
///   u_ss = command_offset + command_per_velocity·v_ref + command_per_acceleration·a_ref.
///
/// The filter gains are per step, so a law stepped at another rate than the one its gains
/// were designed at is given the gains of that rate (filter_gain_at_rate).
class ForwardBalanceLaw {
 public:
  /// Acceleration of the reference [m/s²]: a step of the wheel speed would kick the body
  /// over (it tilts backward when the wheels leap forward).
  static constexpr double kMaxAcceleration = 2.0;
  /// Bound of the velocity error's integral [m]: a command the robot cannot follow does not
  /// wind it up.
  static constexpr double kMaxPositionError = 5.0;

  /// @param velocity_filter_gain     Low-pass gain of v̂ per step, in (0, 1].
  /// @param acceleration_filter_gain Low-pass gain of a_ref per step, in (0, 1].
  ForwardBalanceLaw(const VelocityBalancerGains& gains, double timestep,
                    double velocity_filter_gain, double acceleration_filter_gain);

  /// Clears the filters and the integral (at rest).
  void reset();

  /// Steps the reference, the filters and the integral once; returns u [m/s] (plus the
  /// excitation). Allocation-free.
  double ground_velocity(const ForwardBalanceInputs& inputs);

  /// Adds `offset` [m/s] to the ground velocity of the next steps (0 by default).
  void set_excitation(double offset) { excitation_ = offset; }
  /// v̂ after the last step [m/s].
  double filtered_velocity() const { return filtered_velocity_; }
  /// u of the last step [m/s].
  double last_ground_velocity() const { return ground_velocity_; }

 private:
  VelocityBalancerGains gains_;
  double timestep_;
  double velocity_filter_gain_;
  double acceleration_filter_gain_;
  double excitation_ = 0.0;
  double position_error_ = 0.0;          ///< e = ∫(v̂ - v_ref) dt [m]
  double reference_velocity_ = 0.0;      ///< v_ref [m/s]
  double reference_acceleration_ = 0.0;  ///< a_ref [m/s²]
  double filtered_velocity_ = 0.0;       ///< v̂ [m/s]
  double ground_velocity_ = 0.0;         ///< u [m/s]
};

/// The per-step gain of a first-order low-pass filter whose gain is `gain` per step of
/// `designed_timestep`, for steps of `timestep`: the same time constant at another rate
/// (`gain` itself, to the bit, at the designed rate).
double filter_gain_at_rate(double gain, double designed_timestep, double timestep);

}  // namespace upkie_rl
