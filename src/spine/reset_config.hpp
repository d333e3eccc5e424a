#pragma once
/// @file
/// The configuration an agent sends with Start (spine.md section 2), and the reset state
/// the spine reads back from it.

#include <Eigen/Core>
#include <msgpack.hpp>

#include "sim/imu_uncertainty.hpp"
#include "sim/reset_state.hpp"
#include "sim/servo_law.hpp"
#include "spine/dictionary.hpp"

namespace upkie_rl {

/// Robot parameters the Start configuration carries besides the reset state.
struct SpineStartParameters {
  double kp = 20.0;            ///< bullet.torque_control.kp [N.m/rad].
  double kd = 1.0;             ///< bullet.torque_control.kd [N.m.s/rad].
  double wheel_radius = 0.05;  ///< Signed radii are +r (left) and -r (right) [m].
  /// base_orientation.rotation_base_to_imu (sent as 9 floats, row-major).
  Eigen::Matrix3d rotation_base_to_imu = Eigen::Vector3d(-1.0, 1.0, -1.0).asDiagonal();
};

/// Packs the Start configuration into `buffer`, replacing its contents: bullet.reset.*
/// from `state`, bullet.torque_control, wheel_odometry.signed_radius,
/// base_orientation.rotation_base_to_imu, floor_contact.upper_leg_torque_threshold 10.0 and
/// the wheel_contact parameters, all reals float64, keys sorted.
void write_start_config_msgpack(const ResetState& state, const SpineStartParameters& parameters,
                                msgpack::sbuffer& buffer);

/// The reset state in a spine configuration: each of bullet.reset.{position_base_in_world
/// [3], orientation_base_in_world [w,x,y,z], linear_velocity_base_to_world_in_world [3],
/// angular_velocity_base_in_base [3], joint_configuration [6]} that is present replaces
/// the default of ResetState. The orientation is normalised.
/// @throws SpineError naming the key with a wrong type, length, a non-finite value or a
///         zero quaternion.
ResetState reset_state_from_config(const Dictionary& config);

/// The servo gains in a spine configuration: bullet.torque_control.kp and .kd, each
/// replacing its value in `defaults` when present (the public Bullet spine reads them at
/// every Start).
/// @throws SpineError naming the key that is not a finite non-negative number.
ServoGains servo_gains_from_config(const Dictionary& config, const ServoGains& defaults);

/// The IMU uncertainty in a spine configuration: bullet.imu_uncertainty.{accelerometer_bias
/// [3], accelerometer_noise, gyroscope_bias [3], gyroscope_noise} (the public Bullet
/// spine's), each absent key zero.
/// @throws SpineError naming the key with a wrong type or length, a non-finite value or a
///         negative deviation.
ImuUncertainty imu_uncertainty_from_config(const Dictionary& config);

/// What a simulation spine takes from each Start configuration.
struct SpineStartSettings {
  ServoGains servo_gains;
  ImuUncertainty imu_uncertainty;
};

}  // namespace upkie_rl
