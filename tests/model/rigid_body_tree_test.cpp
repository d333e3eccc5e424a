#include "model/rigid_body_tree.hpp"

#include <gtest/gtest.h>

namespace upkie_rl {
namespace {

const RobotModel& model() { return *RobotModel::default_model(); }

const Link& link(const std::string& name) { return model().links()[*model().find_link(name)]; }

TEST(LinkInertiaTest, BoxRuleMatchesBulletForCylinders) {
  // Values PyBullet simulates (robot.md section 3).
  const Eigen::Vector3d stator =
      link_inertia(link("left_hip_qdd100_stator"), InertiaSource::kBulletBoxRule).diagonal();
  EXPECT_NEAR(stator.x(), 4.908e-4, 1e-7);
  EXPECT_NEAR(stator.z(), 8.802e-4, 1e-7);
  const Eigen::Vector3d femur =
      link_inertia(link("left_femur"), InertiaSource::kBulletBoxRule).diagonal();
  EXPECT_NEAR(femur.x(), 3.344e-4, 1e-7);
  EXPECT_NEAR(femur.z(), 8.4e-6, 1e-8);
  const Eigen::Vector3d horn =
      link_inertia(link("left_hip_horn"), InertiaSource::kBulletBoxRule).diagonal();
  EXPECT_NEAR(horn.x(), 5.421e-5, 1e-8);
  EXPECT_NEAR(horn.z(), 2.753e-5, 1e-8);
  const Eigen::Vector3d tire =
      link_inertia(link("left_wheel_tire"), InertiaSource::kBulletBoxRule).diagonal();
  EXPECT_NEAR(tire.x(), 9.697e-5, 1e-8);
  EXPECT_NEAR(tire.z(), 1.632e-4, 1e-7);
}

TEST(LinkInertiaTest, BoxRuleIsExactForBoxes) {
  const Eigen::Vector3d torso =
      link_inertia(link("torso"), InertiaSource::kBulletBoxRule).diagonal();
  EXPECT_NEAR(torso.x(), 7.61667e-3, 1e-8);
  EXPECT_NEAR(torso.y(), 6.51042e-3, 1e-8);
  EXPECT_NEAR(torso.z(), 3.71042e-3, 1e-8);
}

TEST(LinkInertiaTest, UrdfSourceUsesWrittenTensor) {
  EXPECT_NEAR(link_inertia(link("left_hip_qdd100_stator"), InertiaSource::kUrdf)(0, 0), 3.29e-4,
              1e-12);
}

TEST(RigidBodyTreeTest, MergingKeepsSevenBodiesAndTotalMass) {
  const RigidBodyTree tree(model(), InertiaSource::kBulletBoxRule, true);
  ASSERT_EQ(tree.bodies().size(), 7u);
  double mass = 0.0;
  for (const auto& body : tree.bodies()) {
    mass += body.mass;
  }
  EXPECT_NEAR(mass, 5.33922, 1e-9);
  EXPECT_NEAR(tree.bodies()[tree.servo_body(kLeftWheel)].mass, 0.18455, 1e-9);
  EXPECT_NEAR(tree.bodies()[tree.servo_body(kRightWheel)].mass, 0.18455, 1e-9);
}

/// Whole-robot COM and inertia about it, at q = 0, in the root frame.
std::pair<Eigen::Vector3d, Eigen::Matrix3d> whole_body(const RigidBodyTree& tree) {
  std::vector<Eigen::Isometry3d> pose(tree.bodies().size());
  double mass = 0.0;
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < tree.bodies().size(); ++i) {
    const auto& body = tree.bodies()[i];
    pose[i] = body.parent_body < 0 ? Eigen::Isometry3d::Identity()
                                   : pose[body.parent_body] * body.joint_pose_in_parent;
    mass += body.mass;
    weighted += body.mass * (pose[i] * body.principal_frame).translation();
  }
  const Eigen::Vector3d com = weighted / mass;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < tree.bodies().size(); ++i) {
    const auto& body = tree.bodies()[i];
    const Eigen::Isometry3d frame = pose[i] * body.principal_frame;
    const Eigen::Vector3d offset = frame.translation() - com;
    inertia += frame.linear() * body.principal_inertia.asDiagonal() * frame.linear().transpose() +
               body.mass * (offset.squaredNorm() * Eigen::Matrix3d::Identity() -
                            offset * offset.transpose());
  }
  return {com, inertia};
}

TEST(RigidBodyTreeTest, MergingPreservesComAndInertia) {
  for (auto source : {InertiaSource::kBulletBoxRule, InertiaSource::kUrdf}) {
    const auto [merged_com, merged_inertia] = whole_body(RigidBodyTree(model(), source, true));
    const auto [com, inertia] = whole_body(RigidBodyTree(model(), source, false));
    EXPECT_TRUE(merged_com.isApprox(com, 1e-12));
    EXPECT_TRUE(merged_inertia.isApprox(inertia, 1e-10));
  }
}

TEST(RigidBodyTreeTest, WholeBodyComMatchesDescription) {
  const auto [com, inertia] = whole_body(RigidBodyTree(model(), InertiaSource::kUrdf, true));
  EXPECT_TRUE(com.isApprox(Eigen::Vector3d(-0.00599, 0.0, -0.24544), 1e-3)) << com.transpose();
}

TEST(RigidBodyTreeTest, PrincipalFramesAreRotations) {
  const RigidBodyTree tree(model(), InertiaSource::kBulletBoxRule, true);
  for (const auto& body : tree.bodies()) {
    EXPECT_NEAR(body.principal_frame.linear().determinant(), 1.0, 1e-9) << body.name;
    EXPECT_TRUE((body.principal_inertia.array() > 0.0).all()) << body.name;
  }
}

}  // namespace
}  // namespace upkie_rl
