#include "identify/measured_reset_state.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

namespace upkie_rl {

namespace {

/// Link poses in the base frame at the measured joint angles.
std::vector<Eigen::Isometry3d> link_poses(const RobotModel& model, const Observation& observation) {
  std::vector<int> servo_of_joint(model.joints().size(), -1);
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    servo_of_joint[model.servo_joint(servo)] = static_cast<int>(servo);
  }
  std::vector<Eigen::Isometry3d> poses(model.links().size(), Eigen::Isometry3d::Identity());
  for (std::size_t link = 0; link < model.links().size(); ++link) {  // parents come first
    const int joint_index = model.links()[link].parent_joint;
    if (joint_index < 0) continue;
    const Joint& joint = model.joints()[joint_index];
    Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
    if (servo_of_joint[joint_index] >= 0) {
      const double angle = observation.servo[servo_of_joint[joint_index]].position;
      motion.linear() = Eigen::AngleAxisd(angle, joint.axis.normalized()).toRotationMatrix();
    }
    poses[link] = poses[joint.parent_link] * joint.origin * motion;
  }
  return poses;
}

/// A tire's lowest point and the velocity the joints between it and the base give that
/// point, both relative to the base and in world axes.
struct TireContact {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d joint_velocity = Eigen::Vector3d::Zero();
};

TireContact tire_contact(const RobotModel& model, const std::vector<Eigen::Isometry3d>& poses,
                         const Eigen::Matrix3d& orientation, const Observation& observation,
                         std::size_t wheel) {
  const int wheel_joint = model.servo_joint(wheel);
  const Joint& joint = model.joints()[wheel_joint];
  const Eigen::Isometry3d& wheel_pose = poses[joint.child_link];
  const Eigen::Vector3d axis = (orientation * wheel_pose.linear() * joint.axis).normalized();
  const Eigen::Vector3d centre = orientation * wheel_pose.translation();
  Eigen::Vector3d down = -Eigen::Vector3d::UnitZ() + axis.z() * axis;  // in the wheel's plane
  down.normalize();
  TireContact contact;
  contact.point = centre + model.wheel_radius() * down;
  // Each joint from the tire up to the base turns the contact point about its axis.
  for (int link = joint.child_link; link >= 0 && model.links()[link].parent_joint >= 0;) {
    const int joint_index = model.links()[link].parent_joint;
    const Joint& up = model.joints()[joint_index];
    for (std::size_t servo = 0; servo < kNumServos; ++servo) {
      if (model.servo_joint(servo) != joint_index) continue;
      const Eigen::Isometry3d& frame = poses[up.child_link];
      const Eigen::Vector3d joint_axis = (orientation * frame.linear() * up.axis).normalized();
      const Eigen::Vector3d origin = orientation * frame.translation();
      contact.joint_velocity +=
          observation.servo[servo].velocity * joint_axis.cross(contact.point - origin);
    }
    link = up.parent_link;
  }
  return contact;
}

}  // namespace

ResetState measured_reset_state(const RobotModel& model, const Observation& observation) {
  const Eigen::Matrix3d& orientation = observation.base_orientation.rotation_base_to_world;
  const std::vector<Eigen::Isometry3d> poses = link_poses(model, observation);
  const Eigen::Vector3d angular_velocity_world =
      orientation * observation.base_orientation.angular_velocity;
  ResetState state;
  state.orientation_base_in_world = Eigen::Quaterniond(orientation).normalized();
  state.angular_velocity_base_in_base = observation.base_orientation.angular_velocity;
  double lowest = 0.0;
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  for (std::size_t wheel : {kLeftWheel, kRightWheel}) {
    const TireContact contact = tire_contact(model, poses, orientation, observation, wheel);
    lowest = std::min(lowest, contact.point.z());
    // Rolling without slipping: the contact point of the tire is at rest.
    velocity -= 0.5 * (angular_velocity_world.cross(contact.point) + contact.joint_velocity);
  }
  state.position_base_in_world = Eigen::Vector3d(0.0, 0.0, -lowest);
  state.linear_velocity_base_to_world_in_world = velocity;
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    state.joint_configuration[servo] = observation.servo[servo].position;
    state.joint_velocities[servo] = observation.servo[servo].velocity;
  }
  return state;
}

}  // namespace upkie_rl
