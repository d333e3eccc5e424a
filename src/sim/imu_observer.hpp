#pragma once
/// @file
/// ImuObserver: the IMU of a simulated robot, from the base state at each agent step.

#include <random>

#include "model/robot_model.hpp"
#include "sim/imu_uncertainty.hpp"
#include "sim/measured_state.hpp"
#include "sim/observation.hpp"

namespace upkie_rl {

/// Orientation (in the attitude reference frame), angular velocity and linear
/// accelerations of the IMU. The acceleration is the IMU's mean acceleration between two
/// observations: the change of its velocity divided by the time between them.
///
/// Why: observations come once per agent step, after all its physics substeps. Dividing
/// that change by one physics step (the public Bullet spine's formula, which observes
/// every physics step) read nb_substeps times the acceleration: 5 times on 200 Hz spine
/// logs, 10 times in training at 2 ms. Integrated over a log, the mean acceleration gives
/// back the IMU's velocity change, which identification's slip check relies on.
class ImuObserver {
 public:
  /// @param observation_period  Time between two observations, one agent step [s].
  /// @param gravity             Magnitude along -z [m/s^2].
  ImuObserver(const RobotModel& model, double observation_period, double gravity);

  /// Starts a new episode at `base`: the next acceleration differentiates from its velocity,
  /// and `imu` reads zero acceleration (gravity only).
  void reset(const MeasuredBase& base, ImuObservation& imu);

  void observe(const MeasuredBase& base, ImuObservation& imu);

  /// Adds the bias and a draw of white noise of `uncertainty` to the angular velocity and
  /// both accelerations of `imu`; returns the angular velocity error in the base frame
  /// (what an attitude observer built on the gyroscope sees).
  Eigen::Vector3d add_uncertainty(const ImuUncertainty& uncertainty, std::mt19937_64& generator,
                                  ImuObservation& imu) const;

 private:
  Eigen::Vector3d imu_velocity(const MeasuredBase& base) const;

  Eigen::Matrix3d rotation_base_to_imu_;
  Eigen::Vector3d imu_position_in_base_;
  double observation_period_;
  Eigen::Vector3d gravity_world_;
  Eigen::Vector3d previous_velocity_ = Eigen::Vector3d::Zero();
};

}  // namespace upkie_rl
