#pragma once
/// @file
/// The physics backends the engine-parameterised tests run on, made from shared settings.

#include <memory>

#include "sim/bullet_simulation.hpp"
#include "sim/mujoco_simulation.hpp"

namespace upkie_rl::testing {

inline std::unique_ptr<PhysicsSimulation> make_bullet(const PhysicsConfig& physics) {
  BulletConfig config;
  static_cast<PhysicsConfig&>(config) = physics;
  return std::make_unique<BulletSimulation>(RobotModel::default_model(), config);
}

inline std::unique_ptr<PhysicsSimulation> make_mujoco(const PhysicsConfig& physics) {
  MujocoConfig config;
  static_cast<PhysicsConfig&>(config) = physics;
  return std::make_unique<MujocoSimulation>(RobotModel::default_model(), config);
}

}  // namespace upkie_rl::testing
