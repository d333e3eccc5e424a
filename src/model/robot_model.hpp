#pragma once
/// @file
/// RobotModel: the robot description, parsed once from URDF, immutable, shared by every
/// environment (like MuJoCo's mjModel).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "model/joint_order.hpp"
#include "model/wheel_geometry.hpp"

namespace upkie_rl {

/// Raised when a robot description cannot be read; the message names the file and the
/// element at fault.
class ModelError : public Error {
 public:
  using Error::Error;
};

/// Limits of one joint. Continuous joints have infinite position bounds.
struct JointLimits {
  double lower = -std::numeric_limits<double>::infinity();  ///< [rad]
  double upper = std::numeric_limits<double>::infinity();   ///< [rad]
  double velocity = 0.0;  ///< Maximum velocity [rad/s] (not enforced by the simulator).
  double effort = 0.0;    ///< Maximum torque [N.m] (the servo torque clamp).
  bool has_position_limits() const { return std::isfinite(lower) && std::isfinite(upper); }
};

/// A collision primitive attached to a link.
struct CollisionShape {
  enum class Kind { kBox, kCylinder };
  Kind kind = Kind::kBox;
  Eigen::Vector3d box_size = Eigen::Vector3d::Zero();  ///< Full side lengths (box) [m].
  double radius = 0.0;                                 ///< Cylinder radius [m].
  double length = 0.0;                                 ///< Cylinder length along its z axis [m].
  Eigen::Isometry3d pose_in_link = Eigen::Isometry3d::Identity();
};

/// Contact parameters of a link's collision shapes (Bullet URDF `<contact>` extension).
struct ContactParameters {
  double lateral_friction = 0.5;  ///< Bullet's default for links without `<contact>`.
  double rolling_friction = 0.0;
  double stiffness = 0.0;  ///< [N/m]; 0 means a hard contact.
  double damping = 0.0;    ///< [N.s/m].
  bool is_soft() const { return stiffness > 0.0; }
};

/// One link of the description.
struct Link {
  std::string name;
  int parent_joint = -1;  ///< Index into RobotModel::joints(), -1 for the root.
  double mass = 0.0;      ///< [kg]
  /// Inertial frame (origin = centre of mass) in the link frame.
  Eigen::Isometry3d inertial_pose = Eigen::Isometry3d::Identity();
  /// Inertia tensor written in the description, about the COM, in the inertial frame.
  Eigen::Matrix3d urdf_inertia = Eigen::Matrix3d::Zero();
  std::vector<CollisionShape> collisions;
  ContactParameters contact;
};

/// One joint of the description.
struct Joint {
  enum class Type { kFixed, kRevolute, kContinuous };
  std::string name;
  Type type = Type::kFixed;
  int parent_link = -1;
  int child_link = -1;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  ///< Child frame in parent frame.
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();           ///< In the child frame.
  JointLimits limits;
};

/// The robot description: links, joints, and the facts every layer needs (actuated joints
/// in the standard order, wheel radius, track, IMU mounting).
class RobotModel {
 public:
  /// Parses a URDF file.
  /// @throws ModelError naming the file and element when it is missing or malformed, or
  ///         when it lacks what Upkie needs (the six joints, a tire cylinder, an imu link).
  static RobotModel from_urdf_file(const std::filesystem::path& path);

  /// Parses the URDF shipped with upkie-rl (models/upkie/upkie.urdf), once per process.
  static std::shared_ptr<const RobotModel> default_model();

  /// Path of the shipped URDF; the UPKIE_RL_MODEL environment variable overrides it.
  static std::filesystem::path default_urdf_path();

  const std::vector<Link>& links() const { return links_; }
  const std::vector<Joint>& joints() const { return joints_; }
  int root_link() const { return root_link_; }
  std::optional<int> find_link(const std::string& name) const;

  /// Index into joints() of servo `servo` (standard order).
  int servo_joint(std::size_t servo) const { return servo_joints_[servo]; }
  /// Limits of servo `servo` (standard order).
  const JointLimits& servo_limits(std::size_t servo) const {
    return joints_[servo_joints_[servo]].limits;
  }

  /// Total mass [kg].
  double total_mass() const;
  /// Wheel radius [m], read from the left tire's collision cylinder.
  double wheel_radius() const { return wheel_radius_; }
  /// Link holding the tire (largest cylinder rigidly attached) of wheel servo `wheel`
  /// (kLeftWheel or kRightWheel).
  int tire_link(std::size_t wheel) const {
    return wheel == kLeftWheel ? tire_links_[0] : tire_links_[1];
  }
  /// Lateral distance between the two tire centres [m].
  double track() const { return track_; }
  /// Wheel radius and track, to turn base velocities into wheel speeds.
  WheelGeometry wheel_geometry() const { return WheelGeometry{wheel_radius_, track_}; }
  /// Rotation from the base frame to the IMU frame, R_base_to_imu (maps IMU-frame vectors
  /// to base-frame vectors).
  const Eigen::Matrix3d& rotation_base_to_imu() const { return rotation_base_to_imu_; }
  /// Position of the IMU in the base frame [m].
  const Eigen::Vector3d& imu_position_in_base() const { return imu_position_in_base_; }
  /// True when a positive left-wheel velocity rolls the robot forward (Upkie is).
  bool left_wheeled() const { return left_wheeled_; }

  /// Pose of every link in the root frame with all joints at 0.
  std::vector<Eigen::Isometry3d> link_poses_at_zero() const;

  /// Source file.
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::vector<Link> links_;
  std::vector<Joint> joints_;
  int root_link_ = -1;
  std::array<int, kNumServos> servo_joints_{};
  std::array<int, 2> tire_links_{};
  double wheel_radius_ = 0.0;
  double track_ = 0.0;
  Eigen::Matrix3d rotation_base_to_imu_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d imu_position_in_base_ = Eigen::Vector3d::Zero();
  bool left_wheeled_ = true;
};

}  // namespace upkie_rl
