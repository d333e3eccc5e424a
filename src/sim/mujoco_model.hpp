#pragma once
/// @file
/// MuJoCo's model of Upkie, built at load time from the parsed URDF (RobotModel) through
/// the same RigidBodyTree as Bullet's, so both engines simulate the same bodies: masses,
/// centres of mass, principal inertias, joint frames, axes and limits, collision shapes.

#include <array>
#include <memory>

#include "model/rigid_body_tree.hpp"
#include "model/robot_model.hpp"
#include "sim/mujoco_config.hpp"

struct mjModel_;
struct mjData_;

namespace upkie_rl {

struct MujocoModelDeleter {
  void operator()(mjModel_* model) const;
};
struct MujocoDataDeleter {
  void operator()(mjData_* data) const;
};
using MujocoModelPtr = std::unique_ptr<mjModel_, MujocoModelDeleter>;
using MujocoDataPtr = std::unique_ptr<mjData_, MujocoDataDeleter>;

/// Where the robot's parts are in a compiled mjModel.
struct MujocoRobotIndex {
  int root_body = -1;                        ///< Body of the base link.
  int root_qpos = -1;                        ///< Free joint: position then quaternion.
  int root_dof = -1;                         ///< Free joint: linear then angular.
  std::array<int, kNumServos> servo_qpos{};  ///< qpos address of each servo joint.
  std::array<int, kNumServos> servo_dof{};   ///< dof address of each servo joint.
  std::array<int, kNumServos> servo_body{};  ///< Body each servo joint moves.
  std::array<int, 2> tire_geoms{-1, -1};     ///< Left, right tire geoms.
  int floor_geom = -1;                       ///< -1 without a floor.
  /// The bumps across the floor (PhysicsConfig::bumps) are the geoms first_bump_geom to
  /// first_bump_geom + num_bump_geoms - 1; none by default.
  int first_bump_geom = -1;
  int num_bump_geoms = 0;

  /// Whether `geom` is the floor or a bump on it: what a robot geom touches.
  bool is_ground(int geom) const {
    return (geom == floor_geom && geom >= 0) ||
           (geom >= first_bump_geom && geom < first_bump_geom + num_bump_geoms);
  }
};

/// A compiled model with its index. Immutable once built; shared by every simulation and
/// renderer made from the same settings.
struct MujocoModel {
  MujocoModelPtr model;
  MujocoRobotIndex index;
};

/// Builds Upkie (free base, hinge joints with the URDF limits, collision shapes, the tires'
/// contact parameters) and, with config.floor, a checkered floor plane at z = 0 with the
/// bumps of config.bumps, and a light.
/// @throws std::invalid_argument on a setting out of its domain (MujocoConfig::validate).
/// @throws ModelError with MuJoCo's compiler message if the model does not compile.
std::shared_ptr<const MujocoModel> build_mujoco_model(const RobotModel& robot,
                                                      const MujocoConfig& config);

/// Makes MuJoCo report warnings through spdlog instead of its log file (once per process).
void route_mujoco_messages();

}  // namespace upkie_rl
