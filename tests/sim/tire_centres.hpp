#pragma once
/// @file
/// Where the tires' centres are, from a simulated observation's ground truth: what a bump
/// lifts, whatever the base's pitch does meanwhile.

#include <Eigen/Geometry>

#include "model/rigid_body_tree.hpp"
#include "sim/observation.hpp"

namespace upkie_rl::testing {

/// The centre of each tire's collision cylinder in the world frame, through the base pose
/// and the measured joint angles.
class TireCentres {
 public:
  explicit TireCentres(const RobotModel& model)
      : model_(model), tree_(model, InertiaSource::kUrdf, /*merge_fixed_links=*/true) {}

  /// Centre of tire `wheel` (kLeftWheel or kRightWheel) [m].
  Eigen::Vector3d operator()(const Observation& observation, std::size_t wheel) const {
    const int link = model_.tire_link(wheel);
    const int body = tree_.body_of_link(link);
    Eigen::Isometry3d centre_in_body = Eigen::Isometry3d::Identity();
    for (const BodyCollision& collision : tree_.bodies()[body].collisions) {
      if (collision.link == link) centre_in_body = collision.shape.pose_in_link;
    }
    Eigen::Isometry3d base_in_world = Eigen::Isometry3d::Identity();
    base_in_world.linear() = observation.sim_base.orientation.toRotationMatrix();
    base_in_world.translation() = observation.sim_base.position;
    return (base_in_world * body_in_root(observation, body) * centre_in_body).translation();
  }

 private:
  /// Pose of body `body` in the root (base link) frame at the measured joint angles.
  Eigen::Isometry3d body_in_root(const Observation& observation, int body) const {
    const RigidBody& rigid_body = tree_.bodies()[body];
    if (rigid_body.parent_body < 0) return Eigen::Isometry3d::Identity();
    double angle = 0.0;
    for (std::size_t servo = 0; servo < kNumServos; ++servo) {
      if (tree_.servo_body(servo) == body) angle = observation.servo[servo].position;
    }
    return body_in_root(observation, rigid_body.parent_body) * rigid_body.joint_pose_in_parent *
           Eigen::AngleAxisd(angle, rigid_body.joint_axis);
  }

  const RobotModel& model_;
  RigidBodyTree tree_;
};

}  // namespace upkie_rl::testing
