#pragma once
/// @file
/// The full observation of the robot as a typed struct. This is what every backend
/// produces after a step; the nested-dictionary view (JSON, msgpack) with the key names of
/// the Upkie spine is built from it only where a user or the spine asks for it.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

#include "model/joint_order.hpp"

namespace upkie_rl {

/// `servo.<joint>.*`: one servo's measurements.
struct ServoObservation {
  double position = 0.0;     ///< Joint angle [rad].
  double velocity = 0.0;     ///< Joint velocity [rad/s].
  double torque = 0.0;       ///< Torque applied by the servo law [N.m].
  double temperature = 0.0;  ///< Servo temperature [deg C].
  double voltage = 0.0;      ///< Power bus voltage [V].
};

/// `imu.*`: the inertial measurement unit, in its own frame (x backward, y left, z down).
struct ImuObservation {
  /// Orientation of the IMU frame in the attitude reference frame (x forward, y right,
  /// z down).
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();         ///< [rad/s], IMU frame.
  Eigen::Vector3d linear_acceleration = Eigen::Vector3d::Zero();      ///< Gravity-free [m/s^2].
  Eigen::Vector3d raw_linear_acceleration = Eigen::Vector3d::Zero();  ///< Including -g [m/s^2].
};

/// `base_orientation.*`: attitude of the base.
struct BaseOrientationObservation {
  /// Pitch angle of the base [rad], positive when leaning forward; independent of yaw.
  double pitch = 0.0;
  /// Angular velocity of the base in the base frame [rad/s]; [1] is the pitch rate.
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
  /// Rotation matrix from the base frame to the world frame.
  Eigen::Matrix3d rotation_base_to_world = Eigen::Matrix3d::Identity();
};

/// `wheel_odometry.*`: position and velocity of the average wheel contact point.
struct WheelOdometryObservation {
  double position = 0.0;  ///< [m], forward positive, zero at reset.
  double velocity = 0.0;  ///< [m/s].
};

/// `floor_contact.*`.
struct FloorContactObservation {
  bool contact = false;  ///< True when a tire touches the floor.
  /// True when a part other than a tire (legs, base) touches the floor: ground truth that
  /// physics backends fill (a real robot does not measure it; it stays false there).
  bool non_wheel = false;
};

/// `sim.base.*`: ground truth of the base link, simulation only.
struct SimBaseObservation {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();               ///< Base origin in world [m].
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< Base in world.
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();   ///< Of the base origin, world [m/s].
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  ///< In the base frame [rad/s].
};

/// Everything a backend observes after a step.
struct Observation {
  double time = 0.0;                                 ///< Simulated (or spine) time since reset [s].
  std::array<ServoObservation, kNumServos> servo{};  ///< In the standard joint order.
  ImuObservation imu;
  BaseOrientationObservation base_orientation;
  WheelOdometryObservation wheel_odometry;
  FloorContactObservation floor_contact;
  /// Ground truth, filled by simulation backends only (has_sim is false on a real robot).
  bool has_sim = false;
  SimBaseObservation sim_base;
  /// Joint angles used for the ground truth record (same as servo positions in simulation).
};

}  // namespace upkie_rl
