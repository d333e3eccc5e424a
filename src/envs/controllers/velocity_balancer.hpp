#pragma once
/// @file
/// VelocityBalancer: the classical baseline of the velocity task. Legs at the crouch pose of
/// the commanded base height (leg inverse kinematics, the wheel under the hip, as Upkie's
/// pink balancer crouches; straight without a height command); the wheels driven by a linear
/// balance law that tracks the commanded forward velocity (a wheeled inverted pendulum with a
/// velocity reference and an integral state), plus a differential wheel speed for the yaw rate.

#include <array>

#include "envs/controllers/controller.hpp"
#include "envs/controllers/forward_balance_law.hpp"
#include "envs/controllers/velocity_balancer_gains.hpp"
#include "envs/core/env.hpp"
#include "envs/tasks/leg_kinematics.hpp"
#include "model/wheel_geometry.hpp"

namespace upkie_rl {

/// With θ the pitch (from the gravity vector of the observation), θ̇ the gyroscope's pitch
/// rate, v̂ the wheel odometry velocity r(ω_left - ω_right)/2 low-pass filtered (the tire
/// contact makes the wheel speeds jitter by several tenths of a m/s from one step to the
/// next), v* and ψ̇* the command, v_ref a reference ramping toward v* at most at 2 m/s²
/// (the command's own acceleration when it ramps slower, VelocityCommandLimiter), a_ref its
/// acceleration low-pass filtered and e the integral of v̂ - v_ref since reset (bounded to
/// ±5 m):
///
///   ground velocity u = u_ss + k·[θ - θ_ss, θ̇, v̂ - v_ref, e],
///   θ_ss = pitch_offset + pitch_per_velocity·v_ref + pitch_per_acceleration·a_ref,
///   u_ss = command_offset + command_per_velocity·v_ref + command_per_acceleration·a_ref
///   (the steady state of a robot driving at v_ref and accelerating at a_ref: it leans
///   into the acceleration),
///   yaw rate ω = ψ̇* + k_ψ(ψ̇* - ψ̇) + k_ψi∫(ψ̇* - ψ̇) with ψ̇ the gyroscope's yaw rate,
///   ω_left = u/r - (track/2)/r·ω,  ω_right = -u/r - (track/2)/r·ω
///
/// written as the normalised wheel actions of the velocity task. Legs: with a height
/// command h* in the observation, hips and knees track the crouch pose of h*
/// (LegKinematics::crouch_pose: hips (+h, -h), knees (k, -k), the wheel axle under the
/// hip), as normalised actions of the task's leg_action_scale (clamped to ±1), no lower
/// than the crouch whose shins tilt kCrouchShinTilt minus kCrouchLeanGain times the
/// forward lean (so that the ankles clear the floor while the robot leans forward);
/// otherwise straight (actions 0). Everything is held still (actions 0) for kTouchdownTime after
/// reset.
class VelocityBalancer final : public Controller {
 public:
  /// The agent step the filter gains below are given for [s] (the task's 50 Hz); at another
  /// rate the balancer takes the gains of the same time constants (filter_gain_at_rate).
  static constexpr double kFilterDesignTimestep = 0.02;
  /// Low-pass gain of the velocity estimate per agent step of kFilterDesignTimestep.
  static constexpr double kVelocityFilterGain = 0.15;
  /// Low-pass gain of a_ref per agent step: the lean comes in over a few steps instead
  /// of a step of the pitch reference when the command starts to ramp.
  static constexpr double kAccelerationFilterGain = 0.3;
  /// Proportional and integral gains of the yaw-rate loop ([1], [1/s]).
  static constexpr double kYawRateGain = 0.5;
  static constexpr double kYawRateIntegralGain = 1.0;
  /// Time after reset during which the wheels are held still [s]. The simulators release
  /// the robot 4.5 cm above the floor (ResetState): its wheels touch down after about
  /// 0.1 s. Driven in the air, an unloaded wheel follows its command at once, so the
  /// odometry reads the balancer's own command as the robot's velocity, and the velocity
  /// feedback (k_v > 1) runs away: the wheels met the floor at up to 3 m/s and the robot
  /// fell in 3 of 20 starts on Bullet and 9 of 20 on MuJoCo with tires that grip.
  static constexpr double kTouchdownTime = 0.12;
  /// The crouch is limited to the pose whose shins tilt by kCrouchShinTilt minus
  /// kCrouchLeanGain times the forward lean [rad, 1]: the ankles' collision boxes touch the
  /// floor beyond kMaxShinTilt (0.38 rad) in the world, and driving leans the robot. With
  /// kMaxShinTilt and a gain of 0 the baseline fell on its ankles in 12 of 20 episodes of
  /// random commands (heights down to 0.53 m) on MuJoCo (11 on Bullet); with 0.38 and 1,
  /// 4 (8); with 0.34 and 2, none on either engine, and standing it crouches to 0.535 m
  /// when asked 0.53 m (0.30 and 2: none either, but 0.540 m).
  static constexpr double kCrouchShinTilt = 0.34;
  static constexpr double kCrouchLeanGain = 2.0;

  /// @throws std::invalid_argument when `env` is not a velocity environment, or one with
  ///         relative_wheel_action or wheel_command_feedforward (the balancer computes
  ///         whole wheel targets).
  VelocityBalancer(const Env& env, const VelocityBalancerGains& gains);

  void reset() override;
  void act(std::span<const float> observation, std::span<float> action) override;

  /// The balancer's wheel law with `gains` stepped every `timestep` [s], its filters at
  /// the time constants of kVelocityFilterGain and kAccelerationFilterGain: the one law of
  /// the balancer and of the identification's excitation.
  static ForwardBalanceLaw forward_law(const VelocityBalancerGains& gains, double timestep);

  /// Adds `offset` [m/s] to the ground velocity of the next actions (excitation for the
  /// identification of envs/controllers/velocity_balancer_design.hpp; 0 otherwise).
  void set_excitation(double offset) { forward_.set_excitation(offset); }
  /// v̂ after the last act() [m/s].
  double filtered_velocity() const { return forward_.filtered_velocity(); }
  /// u of the last act() [m/s].
  double ground_velocity() const { return forward_.last_ground_velocity(); }

 private:
  /// Writes the leg actions of the crouch pose of the observation's height command.
  void crouch(std::span<const float> observation, std::span<float> action) const;
  /// Writes the leg actions that give the joint angles `angles` (kLegJoints order) under
  /// the task's action origin.
  void write_leg_actions(std::span<const float> observation, const std::array<double, 4>& angles,
                         std::span<float> action) const;
  /// The observation's height command [m]; refuses an observation without one.
  static double commanded_height(std::span<const float> observation);

  ForwardBalanceLaw forward_;
  WheelGeometry wheels_;
  double wheel_velocity_scale_;           ///< rad/s at action 1
  double leg_action_scale_;               ///< rad at action 1
  bool leg_action_about_crouch_ = false;  ///< Leg actions about the commanded crouch.
  bool height_command_ = false;           ///< Whether the env commands a height (crouch by IK).
  LegKinematics legs_;
  double timestep_;
  int touchdown_steps_;  ///< kTouchdownTime in agent steps
  int steps_since_reset_ = 0;
  double yaw_rate_error_integral_ = 0.0;  ///< ∫(ψ̇* - ψ̇) dt [rad]
};

/// Pitch of the base from the velocity task's observation [rad] (positive leaning forward).
double velocity_task_pitch(std::span<const float> observation);
/// Pitch rate from the velocity task's observation (gyroscope) [rad/s].
double velocity_task_pitch_rate(std::span<const float> observation);

}  // namespace upkie_rl
