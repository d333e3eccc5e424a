#pragma once
/// @file
/// MockSimulation: a backend without physics, for tests and for running the environment
/// stack without Bullet or a robot.

#include <memory>

#include "model/robot_model.hpp"
#include "sim/simulation.hpp"

namespace upkie_rl {

/// A backend that never touches physics. After reset it reports a fixed, plausible
/// observation of Upkie standing upright (pitch 0, IMU at rest, floor contact, servos at
/// 42 deg C and 18 V) with the joint angles of the reset state. Each step echoes the
/// commands: a joint's measured position becomes its commanded position (or, with NaN
/// position, integrates its commanded velocity), its measured velocity becomes the
/// commanded velocity, its torque the feedforward torque within the torque limit; wheel
/// odometry follows the echoed wheel velocities. Time advances by the agent timestep.
class MockSimulation final : public Simulation {
 public:
  /// @param model Robot description (joint limits, wheel radius).
  /// @param agent_timestep Duration of one step [s], > 0.
  /// @throws std::invalid_argument on a null model or a non-positive timestep.
  explicit MockSimulation(std::shared_ptr<const RobotModel> model, double agent_timestep = 0.005);

  const Observation& reset(const ResetState& state) override;

  /// @throws InvalidCommandError on a non-finite velocity, torque or gain (as Bullet does).
  const Observation& step(const ServoAction& action) override;

  const Observation& observation() const override { return observation_; }
  double agent_timestep() const override { return agent_timestep_; }

 private:
  std::shared_ptr<const RobotModel> model_;
  double agent_timestep_;
  Observation observation_;
};

}  // namespace upkie_rl
