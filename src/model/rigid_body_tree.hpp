#pragma once
/// @file
/// RigidBodyTree: the robot as rigid bodies joined by joints, ready for a physics engine.
/// Links joined by fixed joints can be merged into one body with the same total mass,
/// centre of mass and inertia, which leaves the dynamics unchanged and makes them cheaper.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

#include "model/inertia_source.hpp"
#include "model/robot_model.hpp"

namespace upkie_rl {

/// Collision margin Bullet gives URDF shapes [m]; it also enters the box inertia rule.
inline constexpr double kCollisionMargin = 0.001;

/// A collision shape of a body, in the body frame, with its contact parameters.
struct BodyCollision {
  CollisionShape shape;  ///< pose_in_link is the pose in the body frame.
  ContactParameters contact;
  int link = -1;  ///< Link of the description it comes from.
};

/// One rigid body: a link, or a group of links joined by fixed joints.
struct RigidBody {
  std::string name;      ///< Name of its first link (the one its joint moves).
  int parent_body = -1;  ///< -1 for the root body.
  /// Joint of the description that connects it to its parent body (-1 for the root).
  int joint = -1;
  /// Pose of the joint frame in the parent body's frame at zero joint angle (the body
  /// frame is its first link's frame, which equals the joint frame at zero angle).
  Eigen::Isometry3d joint_pose_in_parent = Eigen::Isometry3d::Identity();
  Eigen::Vector3d joint_axis = Eigen::Vector3d::UnitZ();  ///< In the body frame.
  double mass = 0.0;                                      ///< [kg]
  /// Principal inertial frame (origin at the centre of mass) in the body frame.
  Eigen::Isometry3d principal_frame = Eigen::Isometry3d::Identity();
  Eigen::Vector3d principal_inertia = Eigen::Vector3d::Zero();  ///< [kg.m^2]
  std::vector<int> links;  ///< Links of the description merged into this body.
  std::vector<BodyCollision> collisions;
};

/// Inertia tensor of one link about its centre of mass, in its inertial frame.
Eigen::Matrix3d link_inertia(const Link& link, InertiaSource source);

/// Bodies in topological order (a parent precedes its children).
class RigidBodyTree {
 public:
  /// Builds the tree; with merge_fixed_links, fixed joints disappear into their parents.
  RigidBodyTree(const RobotModel& model, InertiaSource source, bool merge_fixed_links);

  const std::vector<RigidBody>& bodies() const { return bodies_; }
  /// Body holding link `link`, and the link's pose in that body's frame.
  int body_of_link(int link) const { return body_of_link_[link]; }
  const Eigen::Isometry3d& link_pose_in_body(int link) const { return link_in_body_[link]; }
  /// Body moved by servo `servo` (standard order).
  int servo_body(std::size_t servo) const { return servo_bodies_[servo]; }

 private:
  std::vector<RigidBody> bodies_;
  std::vector<int> body_of_link_;
  std::vector<Eigen::Isometry3d> link_in_body_;
  std::array<int, kNumServos> servo_bodies_{};
};

}  // namespace upkie_rl
