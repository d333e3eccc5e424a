#include "sim/wheel_odometry_observer.hpp"

namespace upkie_rl {

void WheelOdometryObserver::reset(const std::array<ServoObservation, kNumServos>& servo) {
  left_origin_ = servo[kLeftWheel].position;
  right_origin_ = servo[kRightWheel].position;
}

void WheelOdometryObserver::observe(const std::array<ServoObservation, kNumServos>& servo,
                                    WheelOdometryObservation& odometry) const {
  const double left_angle = servo[kLeftWheel].position - left_origin_;
  const double right_angle = servo[kRightWheel].position - right_origin_;
  odometry.position = wheels_.forward_motion(left_angle, right_angle);
  odometry.velocity =
      wheels_.forward_motion(servo[kLeftWheel].velocity, servo[kRightWheel].velocity);
}

}  // namespace upkie_rl
