#pragma once
/// @file
/// A Simulation for spine tests: no physics, records what it is asked. Each step advances
/// time by `timestep`, and every joint's position by its commanded velocity * timestep, so
/// tests can tell which action was applied.

#include <unistd.h>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/simulation.hpp"

namespace upkie_rl::testing {

class FakeSimulation final : public Simulation {
 public:
  explicit FakeSimulation(double timestep = 0.005) : timestep_(timestep) {
    observation_.has_sim = true;
  }

  const Observation& reset(const ResetState& state) override {
    resets.push_back(state);
    observation_.time = 0.0;
    for (std::size_t i = 0; i < kNumServos; ++i) {
      observation_.servo[i].position = state.joint_configuration[i];
      observation_.servo[i].velocity = 0.0;
    }
    observation_.sim_base.position = state.position_base_in_world;
    observation_.sim_base.orientation = state.orientation_base_in_world;
    return observation_;
  }

  const Observation& step(const ServoAction& action) override {
    if (throw_on_step) throw SimulationDivergedError("fake divergence");
    actions.push_back(action);
    action_times.push_back(observation_.time);
    observation_.time += timestep_;
    for (std::size_t i = 0; i < kNumServos; ++i) {
      observation_.servo[i].velocity = action[i].velocity;
      observation_.servo[i].position += action[i].velocity * timestep_;
      observation_.servo[i].torque = action[i].feedforward_torque;
    }
    observation_.wheel_odometry.position += 0.01;
    return observation_;
  }

  const Observation& observation() const override { return observation_; }
  double agent_timestep() const override { return timestep_; }

  std::vector<ResetState> resets;
  std::vector<ServoAction> actions;
  std::vector<double> action_times;  ///< Simulation time at which each step began.
  bool throw_on_step = false;

 private:
  double timestep_;
  Observation observation_;
};

/// A shared-memory name no other test (or process) uses.
inline std::string unique_shm_name(const std::string& tag) {
  static int counter = 0;
  return "/upkie_rl_test_" + tag + "_" + std::to_string(::getpid()) + "_" +
         std::to_string(counter++);
}

}  // namespace upkie_rl::testing
