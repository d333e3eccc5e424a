#pragma once
/// @file
/// A short balancing run the floor tests compare bit for bit between worlds.

#include <Eigen/Geometry>
#include <algorithm>
#include <vector>

#include "sim/physics_simulation.hpp"
#include "sim/servo_actions.hpp"

namespace upkie_rl::testing {

/// The base positions of 400 steps (2 s) of the pendulum law from a tilted start.
inline std::vector<Eigen::Vector3d> balance_trajectory(PhysicsSimulation& simulation) {
  ResetState start;
  start.orientation_base_in_world = Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY());
  simulation.reset(start);
  const double radius = simulation.model().wheel_radius();
  std::vector<Eigen::Vector3d> positions;
  for (int step = 0; step < 400; ++step) {
    const Observation& observation = simulation.observation();
    const double velocity = 10.0 * observation.base_orientation.pitch +
                            observation.wheel_odometry.position +
                            0.1 * observation.wheel_odometry.velocity;
    simulation.step(pendulum_action(std::clamp(velocity, -1.0, 1.0), radius));
    positions.push_back(simulation.observation().sim_base.position);
  }
  return positions;
}

}  // namespace upkie_rl::testing
