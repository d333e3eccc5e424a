#pragma once
/// @file
/// MujocoSimulation: Upkie in MuJoCo, behind the same interface and servo law as Bullet.

#include <memory>

#include "model/robot_model.hpp"
#include "sim/mujoco_config.hpp"
#include "sim/mujoco_model.hpp"
#include "sim/physics_simulation.hpp"
#include "sim/simulated_sensors.hpp"

namespace upkie_rl {

/// One robot in its own mjData over a shared, immutable mjModel. Each agent step holds the
/// servo commands for `nb_substeps` physics steps, evaluating the servo law at every one
/// with the joint state of that step (as BulletSimulation does); the observation is read
/// after the last one by the same observers. Not thread-safe; one instance per thread.
class MujocoSimulation final : public PhysicsSimulation {
 public:
  /// @throws std::invalid_argument on a setting out of its domain.
  /// @throws ModelError when MuJoCo cannot compile the robot.
  explicit MujocoSimulation(std::shared_ptr<const RobotModel> model,
                            const MujocoConfig& config = {});
  /// Shares an already compiled model (built from `model` with the same `config`).
  MujocoSimulation(std::shared_ptr<const RobotModel> model, const MujocoConfig& config,
                   std::shared_ptr<const MujocoModel> compiled);
  ~MujocoSimulation() override;
  MujocoSimulation(const MujocoSimulation&) = delete;
  MujocoSimulation& operator=(const MujocoSimulation&) = delete;

  /// Resets every engine variable (warm starts included) and puts the robot in `state`:
  /// a trajectory depends only on its reset state and commands.
  /// @throws std::invalid_argument on a non-finite state.
  const Observation& reset(const ResetState& state) override;

  /// @throws InvalidCommandError on non-finite commands (see validate_servo_action).
  /// @throws SimulationDivergedError when the state becomes non-finite; reset to go on.
  const Observation& step(const ServoAction& action) override;

  const Observation& step_braked() override;

  const Observation& observation() const override { return observation_; }
  const PhysicsConfig& physics_config() const override { return config_; }
  const MujocoConfig& config() const { return config_; }
  const RobotModel& model() const override { return *model_; }
  const MujocoModel& mujoco_model() const { return *compiled_; }

 private:
  const Observation& advance(const ServoAction& action, bool braked);
  void read_observation();
  void measure(MeasuredJoints& joints, MeasuredBase& base) const;
  bool tire_touches_floor() const;

  std::shared_ptr<const RobotModel> model_;
  MujocoConfig config_;
  std::shared_ptr<const MujocoModel> compiled_;
  MujocoDataPtr data_;
  Observation observation_;
  SimulatedSensors sensors_;
  std::array<double, kNumServos> applied_torques_{};
  bool diverged_ = false;
};

}  // namespace upkie_rl
