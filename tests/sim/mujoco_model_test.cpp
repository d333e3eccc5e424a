#include "sim/mujoco_model.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include "model/rigid_body_tree.hpp"
#include "sim/mujoco_simulation.hpp"

namespace upkie_rl {
namespace {

/// MuJoCo's compiled model holds what the description says, body by body: MuJoCo compiles
/// its own copy, so this checks the compilation (units, frames, merging), not the builder's
/// arithmetic against itself.
void expect_model_matches_description(InertiaSource source) {
  const auto robot = RobotModel::default_model();
  MujocoConfig config;
  config.inertia_source = source;
  const auto compiled = build_mujoco_model(*robot, config);
  const mjModel* m = compiled->model.get();
  const RigidBodyTree tree(*robot, source, /*merge_fixed_links=*/true);
  ASSERT_EQ(m->nbody, static_cast<int>(tree.bodies().size()) + 1);  // + world

  double total_mass = 0.0;
  for (const RigidBody& body : tree.bodies()) {
    const int id = mj_name2id(m, mjOBJ_BODY, body.name.c_str());
    ASSERT_GE(id, 0) << body.name;
    EXPECT_NEAR(m->body_mass[id], body.mass, 1e-12) << body.name;
    total_mass += m->body_mass[id];
    // Centre of mass in the body frame.
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(m->body_ipos[3 * id + i], body.principal_frame.translation()[i], 1e-12)
          << body.name;
    }
    // Principal moments, as a sorted set (MuJoCo may order the principal axes its own way).
    std::array<double, 3> expected{body.principal_inertia[0], body.principal_inertia[1],
                                   body.principal_inertia[2]};
    std::array<double, 3> actual{m->body_inertia[3 * id], m->body_inertia[3 * id + 1],
                                 m->body_inertia[3 * id + 2]};
    std::sort(expected.begin(), expected.end());
    std::sort(actual.begin(), actual.end());
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(actual[i], expected[i], 1e-9) << body.name;
  }
  EXPECT_NEAR(total_mass, robot->total_mass(), 1e-9);

  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    const Joint& joint = robot->joints()[robot->servo_joint(servo)];
    const int id = mj_name2id(m, mjOBJ_JOINT, joint.name.c_str());
    ASSERT_GE(id, 0) << joint.name;
    EXPECT_EQ(m->jnt_type[id], mjJNT_HINGE);
    const RigidBody& body = tree.bodies()[tree.servo_body(servo)];
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(m->jnt_axis[3 * id + i], body.joint_axis[i], 1e-12) << joint.name;
    }
    EXPECT_EQ(m->jnt_limited[id] != 0, joint.limits.has_position_limits()) << joint.name;
    if (joint.limits.has_position_limits()) {
      EXPECT_NEAR(m->jnt_range[2 * id], joint.limits.lower, 1e-12) << joint.name;  // radians
      EXPECT_NEAR(m->jnt_range[2 * id + 1], joint.limits.upper, 1e-12) << joint.name;
    }
  }
  // The free base, and tires of the description's radius.
  EXPECT_EQ(m->jnt_type[0], mjJNT_FREE);
  for (int tire : compiled->index.tire_geoms) {
    EXPECT_EQ(m->geom_type[tire], mjGEOM_CYLINDER);
    EXPECT_NEAR(m->geom_size[3 * tire], robot->wheel_radius(), 1e-12);
  }
  EXPECT_GE(compiled->index.floor_geom, 0);
  EXPECT_EQ(m->geom_type[compiled->index.floor_geom], mjGEOM_PLANE);
}

TEST(MujocoModel, MatchesTheDescriptionWithBoxRuleInertias) {
  expect_model_matches_description(InertiaSource::kBulletBoxRule);
}

TEST(MujocoModel, MatchesTheDescriptionWithUrdfInertias) {
  expect_model_matches_description(InertiaSource::kUrdf);
}

TEST(MujocoModel, JointPosesMatchTheDescriptionAtZero) {
  // With every joint at 0 and the base at the origin, each body sits where the description's
  // forward kinematics puts its first link.
  const auto robot = RobotModel::default_model();
  const auto compiled = build_mujoco_model(*robot, MujocoConfig{});
  const mjModel* m = compiled->model.get();
  MujocoDataPtr data(mj_makeData(m));
  data->qpos[3] = 1.0;  // identity quaternion, base at the origin
  mj_kinematics(m, data.get());
  const std::vector<Eigen::Isometry3d> poses = robot->link_poses_at_zero();
  const RigidBodyTree tree(*robot, InertiaSource::kBulletBoxRule, true);
  for (const RigidBody& body : tree.bodies()) {
    const int id = mj_name2id(m, mjOBJ_BODY, body.name.c_str());
    const Eigen::Vector3d expected = poses[body.links.front()].translation();
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(data->xpos[3 * id + i], expected[i], 1e-12) << body.name;
    }
  }
}

TEST(MujocoModel, BadConfigIsRefused) {
  const auto robot = RobotModel::default_model();
  MujocoConfig config;
  config.tire_condim = 4;
  EXPECT_THROW(MujocoSimulation(robot, config), std::invalid_argument);
  config.tire_condim = 3;
  config.solver_iterations = 0;
  EXPECT_THROW(MujocoSimulation(robot, config), std::invalid_argument);
}

}  // namespace
}  // namespace upkie_rl
