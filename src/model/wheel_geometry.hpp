#pragma once

namespace upkie_rl {

/// Joint velocities of the two wheels [rad/s], each in its own joint's sign.
struct WheelVelocities {
  double left = 0.0;
  double right = 0.0;
};

/// The wheels' radius and track: what maps a velocity of the base to wheel speeds. A value
/// so that tasks and controllers keep a copy (RobotModel::wheel_geometry()).
///
/// Why one place: the velocity task's wheel feedforward, its balancer and the ground
/// velocity commander each turned a base velocity into wheel speeds (and the odometry and
/// the balancer wheel speeds back into a velocity), and a sign flipped in
/// one of them turns the robot the wrong way without any error.
struct WheelGeometry {
  double radius = 0.0;  ///< [m]
  double track = 0.0;   ///< lateral distance between the two tire centres [m]

  /// Wheel velocities that roll the base at `forward_velocity` [m/s] while it turns at
  /// `yaw_rate` [rad/s, counter-clockwise seen from above], without slip. Upkie's joint
  /// convention: driving forward turns the left wheel forward (positive) and the right one
  /// backward; both positive spin the robot clockwise.
  WheelVelocities velocities(double forward_velocity, double yaw_rate) const {
    const double forward = forward_velocity / radius;
    const double turn = -(0.5 * track / radius) * yaw_rate;
    return WheelVelocities{forward + turn, -forward + turn};
  }

  /// The base's forward motion [m or m/s] of a motion of the wheels [rad or rad/s, each in
  /// its joint's sign]: the average of the two wheels' rolling, the turn cancelling out.
  /// Linear, so that it maps wheel angles to a travelled distance as well as speeds to a
  /// velocity; the inverse of velocities() for its forward part. The difference is taken in
  /// the arguments' own type: the velocity balancer reads float observations and subtracted
  /// them in float when the checked-in policies were trained, and a double subtraction
  /// changes their returns (by 0.03-0.08 % over 20 s).
  template <typename Real>
  double forward_motion(Real left, Real right) const {
    const Real difference = left - right;
    return 0.5 * difference * radius;
  }
};

}  // namespace upkie_rl
