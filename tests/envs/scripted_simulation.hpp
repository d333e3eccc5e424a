#pragma once
/// @file
/// A test backend whose observations the test writes: to drive environments through states
/// a mock or physics would not reach on demand (falls, drifts, spins).

#include <memory>
#include <vector>

#include "envs/kinds/servos_env.hpp"
#include "model/robot_model.hpp"
#include "sim/simulation.hpp"

namespace upkie_rl::testing {

class ScriptedSimulation final : public Simulation {
 public:
  explicit ScriptedSimulation(double agent_timestep = 0.005) : agent_timestep_(agent_timestep) {}

  /// What the next reset and steps return; a step past the script repeats the last entry.
  Observation on_reset;
  std::vector<Observation> script;
  /// Commands received, one per step.
  std::vector<ServoAction> received;

  const Observation& reset(const ResetState& state) override {
    reset_states.push_back(state);
    observation_ = on_reset;
    next_ = 0;
    return observation_;
  }
  const Observation& step(const ServoAction& action) override {
    validate_servo_action(action);
    received.push_back(action);
    if (!script.empty()) observation_ = script[std::min(next_++, script.size() - 1)];
    return observation_;
  }
  const Observation& observation() const override { return observation_; }
  double agent_timestep() const override { return agent_timestep_; }

  std::vector<ResetState> reset_states;

 private:
  double agent_timestep_;
  Observation observation_;
  std::size_t next_ = 0;
};

/// An observation with the given pendulum state.
inline Observation pendulum_state(double pitch, double position, double pitch_rate,
                                  double velocity) {
  Observation observation;
  observation.base_orientation.pitch = pitch;
  observation.wheel_odometry.position = position;
  observation.base_orientation.angular_velocity.y() = pitch_rate;
  observation.wheel_odometry.velocity = velocity;
  return observation;
}

/// An environment built on a ServosEnv over a ScriptedSimulation, and that simulation.
template <class EnvType>
struct ScriptedEnv {
  ScriptedSimulation* simulation = nullptr;
  std::unique_ptr<EnvType> env;
};

/// Makes an EnvType (PendulumEnv, GyropodEnv, ServosTaskEnv) on a scripted simulation.
template <class EnvType>
ScriptedEnv<EnvType> make_scripted_env() {
  auto simulation = std::make_unique<ScriptedSimulation>();
  ScriptedEnv<EnvType> result;
  result.simulation = simulation.get();
  result.env = std::make_unique<EnvType>(
      std::make_unique<ServosEnv>(std::move(simulation), RobotModel::default_model()));
  return result;
}

}  // namespace upkie_rl::testing
