#pragma once
/// @file
/// PerturbationSettings: the physical perturbations of a simulated environment (masses,
/// frictions, torque and IMU noise, pushes), as options, drawn at each reset.

#include <random>
#include <string>

#include "base/option_table.hpp"
#include "sim/physics_variation.hpp"

namespace upkie_rl {

/// Where a push points, relative to the robot's heading at the push.
enum class PushDirection {
  kSagittal,  ///< Forward or backward, each with probability 1/2.
  kForward,
  kBackward,
  kLateral,  ///< Left or right.
  kAny,      ///< Any horizontal direction.
};

/// Pushes: a horizontal force on the base's centre of mass held for `duration`, starting at
/// a random time in each window of `interval` seconds, the first window at `start`. Forces
/// change at agent steps, so a push lasts a whole number of them.
struct PushSettings {
  double force = 0.0;      ///< Largest magnitude [N]; 0 disables pushes.
  double force_min = 0.0;  ///< Smallest magnitude [N]; drawn uniformly in [force_min, force].
  double duration = 0.1;   ///< [s]
  double start = 0.25;     ///< Start of the first window [s].
  double interval = 1.0;   ///< Length of a window [s], at least the duration.
  PushDirection direction = PushDirection::kSagittal;
  /// With direction kAny: the share of pushes drawn along the heading (forward or backward,
  /// each half of it); the rest point anywhere. 0 (the default) draws as kAny always did.
  double sagittal_share = 0.0;

  bool enabled() const { return force > 0.0; }
};

/// Ranges of the perturbations, all off by default. Randomised values are drawn at each
/// reset from the environment's seeded generator; "randomisation bounds" (everything but
/// the fixed values mass_scale, floor_friction, torque_limit_scale, the gain scales, the
/// slopes, the payload and the *_fixed values) are multiplied by the curriculum scale. The
/// fixed values draw nothing: a seed gives the same episode otherwise.
struct PerturbationSettings {
  double mass_scale = 1.0;         ///< Fixed factor on every body's mass and inertia.
  double inertia_variation = 0.0;  ///< ε: each body's mass and inertia × (1 + U(-ε, ε)).
  double joint_friction = 0.0;     ///< Each joint's kinetic friction in U(0, it) [N.m].
  /// Fixed kinetic friction of every joint, added to the drawn one [N.m].
  double joint_friction_fixed = 0.0;
  double wheel_servo_gain_scale = 1.0;    ///< Fixed factor on the wheel servos' kp and kd.
  double leg_servo_gain_scale = 1.0;      ///< Fixed factor on the hip and knee servos' kp and kd.
  double torque_control_noise = 0.0;      ///< Std of the noise on applied torques [N.m].
  double torque_measurement_noise = 0.0;  ///< Std of the noise on observed torques [N.m].
  double imu_accelerometer_bias = 0.0;    ///< Each bias component in U(-it, it) [m/s^2].
  double imu_accelerometer_noise = 0.0;   ///< Std of the white noise [m/s^2].
  double imu_gyroscope_bias = 0.0;        ///< Each bias component in U(-it, it) [rad/s].
  /// Fixed gyroscope bias, in the IMU's frame, added to the drawn one [rad/s].
  Eigen::Vector3d imu_gyroscope_bias_fixed = Eigen::Vector3d::Zero();
  double imu_gyroscope_noise = 0.0;       ///< Std of the white noise [rad/s].
  double floor_friction = 1.0;            ///< Fixed factor on the tire-floor friction.
  double floor_friction_variation = 0.0;  ///< ε: friction × (1 + U(-ε, ε)).
  double torque_limit_scale = 1.0;        ///< Fixed factor on every servo's torque limit.
  /// Fixed floor slope about the robot's initial lateral axis [deg], positive when it faces
  /// uphill (PhysicsVariation::slope_pitch).
  double slope_pitch = 0.0;
  /// Fixed floor slope about the robot's initial forward axis [deg], positive when the
  /// floor rises to its left (PhysicsVariation::slope_roll).
  double slope_roll = 0.0;
  double payload_mass = 0.0;      ///< Fixed point mass on the base [kg].
  double payload_offset_x = 0.0;  ///< Its offset from the base's centre of mass, forward [m].
  double payload_offset_y = 0.0;  ///< Left [m].
  double payload_offset_z = 0.0;  ///< Up [m].
  /// Randomised floor slope: pitch and roll each plus U(-it, it) at reset [deg] (the
  /// field's "tilted gravity" terrain for a policy that must hold on ramps).
  double slope_variation = 0.0;
  /// Randomised payload: mass plus U(0, it) at reset [kg], an owner's battery or camera.
  double payload_mass_variation = 0.0;
  /// Randomised payload placement: forward and left offsets each plus U(-it, it) [m].
  double payload_offset_variation = 0.0;
  /// Randomised motor weakness: torque limits times 1 - U(0, it) at reset.
  double torque_limit_variation = 0.0;
  /// Share of the episodes whose floor has the world's bumps (bump_height), drawn at reset;
  /// the others have a flat floor. Not scaled by the curriculum. Why: a policy trained on
  /// cable covers in a share of its episodes, without a second kind of environment.
  double bump_share = 1.0;
  PushSettings push;

  /// Whether any setting differs from the nominal robot and world.
  bool any() const;

  /// The variation of one episode, every randomisation bound multiplied by `scale`. Always
  /// the same number of draws, whatever the settings.
  PhysicsVariation sample(std::mt19937_64& generator, double scale) const;

  /// Adds the randomised slope, payload, motor weakness and floor bumps to `variation`, drawn from
  /// a stream derived from its noise seed, every bound multiplied by `scale`.
  void add_randomized_world(PhysicsVariation& variation, double scale) const;

  /// Declares the options (names as the fields, pushes as push_*) in `table`, and
  /// problem() as their rule.
  void declare_options(OptionTable& table);

  /// An inconsistent pair (force_min above force, a push longer than its interval), named;
  /// "" if none.
  std::string problem() const;
  /// @throws std::invalid_argument with problem(), if any.
  void validate() const;
};

}  // namespace upkie_rl
