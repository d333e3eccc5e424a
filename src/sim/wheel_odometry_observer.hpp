#pragma once
/// @file
/// WheelOdometryObserver: ground position and velocity from the two wheel servos.

#include <array>

#include "model/robot_model.hpp"
#include "sim/observation.hpp"

namespace upkie_rl {

/// Odometry of a left-wheeled robot (a positive left-wheel velocity rolls it forward):
/// the average contact point travels r * (left - right) / 2, zero at reset.
class WheelOdometryObserver {
 public:
  explicit WheelOdometryObserver(const RobotModel& model) : wheels_(model.wheel_geometry()) {}

  /// Remembers the wheel angles of the reset state as the origin.
  void reset(const std::array<ServoObservation, kNumServos>& servo);

  void observe(const std::array<ServoObservation, kNumServos>& servo,
               WheelOdometryObservation& odometry) const;

 private:
  WheelGeometry wheels_;
  double left_origin_ = 0.0;   ///< [rad]
  double right_origin_ = 0.0;  ///< [rad]
};

}  // namespace upkie_rl
