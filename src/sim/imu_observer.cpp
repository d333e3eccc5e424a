#include "sim/imu_observer.hpp"

#include "sim/random_draws.hpp"

namespace upkie_rl {
namespace {

/// R_ars_to_world = diag(1, -1, -1): the IMU filter's frame is x forward, y right, z down.
const Eigen::Matrix3d kRotationArsToWorld = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();

}  // namespace

ImuObserver::ImuObserver(const RobotModel& model, double observation_period, double gravity)
    : rotation_base_to_imu_(model.rotation_base_to_imu()),
      imu_position_in_base_(model.imu_position_in_base()),
      observation_period_(observation_period),
      gravity_world_(0.0, 0.0, -gravity) {}

Eigen::Vector3d ImuObserver::imu_velocity(const MeasuredBase& base) const {
  return base.linear_velocity_in_world +
         base.angular_velocity_in_world.cross(base.pose_in_world.linear() * imu_position_in_base_);
}

void ImuObserver::reset(const MeasuredBase& base, ImuObservation& imu) {
  previous_velocity_ = imu_velocity(base);
  observe(base, imu);
}

void ImuObserver::observe(const MeasuredBase& base, ImuObservation& imu) {
  const Eigen::Matrix3d rotation_imu_to_world = base.pose_in_world.linear() * rotation_base_to_imu_;
  imu.orientation =
      Eigen::Quaterniond(kRotationArsToWorld.transpose() * rotation_imu_to_world).normalized();
  imu.angular_velocity = rotation_imu_to_world.transpose() * base.angular_velocity_in_world;
  const Eigen::Vector3d velocity = imu_velocity(base);
  const Eigen::Vector3d acceleration_world = (velocity - previous_velocity_) / observation_period_;
  previous_velocity_ = velocity;
  imu.linear_acceleration = rotation_imu_to_world.transpose() * acceleration_world;
  imu.raw_linear_acceleration =
      rotation_imu_to_world.transpose() * (acceleration_world - gravity_world_);
}

Eigen::Vector3d ImuObserver::add_uncertainty(const ImuUncertainty& uncertainty,
                                             std::mt19937_64& generator,
                                             ImuObservation& imu) const {
  Eigen::Vector3d accelerometer_error = uncertainty.accelerometer_bias;
  Eigen::Vector3d gyroscope_error = uncertainty.gyroscope_bias;
  for (int i = 0; i < 3; ++i) {
    accelerometer_error[i] += uncertainty.accelerometer_noise * standard_normal(generator);
    gyroscope_error[i] += uncertainty.gyroscope_noise * standard_normal(generator);
  }
  imu.linear_acceleration += accelerometer_error;
  imu.raw_linear_acceleration += accelerometer_error;
  imu.angular_velocity += gyroscope_error;
  return rotation_base_to_imu_ * gyroscope_error;
}

}  // namespace upkie_rl
