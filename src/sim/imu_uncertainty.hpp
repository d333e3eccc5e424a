#pragma once
/// @file
/// ImuUncertainty: bias and white noise of a simulated IMU, as the `imu_uncertainty`
/// settings of the public Upkie Bullet spine.

#include <Eigen/Core>

namespace upkie_rl {

/// Errors added to the IMU's angular velocity and linear accelerations at every agent step:
/// the bias, then Gaussian white noise of the given standard deviation on each component.
/// The orientation stays noise-free (as in the public spine). All zero by default.
struct ImuUncertainty {
  Eigen::Vector3d accelerometer_bias = Eigen::Vector3d::Zero();  ///< IMU frame [m/s^2].
  double accelerometer_noise = 0.0;                              ///< Standard deviation [m/s^2].
  Eigen::Vector3d gyroscope_bias = Eigen::Vector3d::Zero();      ///< IMU frame [rad/s].
  double gyroscope_noise = 0.0;                                  ///< Standard deviation [rad/s].

  bool is_zero() const {
    return accelerometer_bias.isZero(0.0) && accelerometer_noise == 0.0 &&
           gyroscope_bias.isZero(0.0) && gyroscope_noise == 0.0;
  }

  /// @throws std::invalid_argument naming the first non-finite value or negative deviation.
  void validate() const;
};

}  // namespace upkie_rl
