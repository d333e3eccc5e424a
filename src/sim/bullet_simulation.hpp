#pragma once
/// @file
/// BulletSimulation: Upkie in a Bullet (double precision, Featherstone btMultiBody) world
/// set up like the reference PyBullet simulation.

#include <memory>

#include "model/rigid_body_tree.hpp"
#include "model/robot_model.hpp"
#include "sim/bullet_config.hpp"
#include "sim/physics_simulation.hpp"
#include "sim/simulated_sensors.hpp"

namespace upkie_rl {

struct BulletWorld;

/// One robot in its own Bullet world. Each agent step holds the servo commands for
/// `nb_substeps` physics steps, re-evaluating the servo law at every physics step with the
/// joint state measured at that step; the observation is read after the last one.
/// Not thread-safe; one instance per thread.
class BulletSimulation final : public PhysicsSimulation {
 public:
  /// @param model  Robot description, shared and immutable.
  /// @throws std::invalid_argument on a setting out of its domain (PhysicsConfig::validate).
  explicit BulletSimulation(std::shared_ptr<const RobotModel> model,
                            const BulletConfig& config = {});
  ~BulletSimulation() override;
  BulletSimulation(const BulletSimulation&) = delete;
  BulletSimulation& operator=(const BulletSimulation&) = delete;

  /// Rebuilds the world and puts the robot in `state`: every episode starts from the same
  /// engine state, so a trajectory depends only on its reset state and commands.
  /// @throws std::invalid_argument on a non-finite state.
  const Observation& reset(const ResetState& state) override;

  /// @throws InvalidCommandError on non-finite commands (see validate_servo_action).
  /// @throws SimulationDivergedError when the state becomes non-finite; reset to go on.
  const Observation& step(const ServoAction& action) override;

  const Observation& step_braked() override;

  const Observation& observation() const override { return observation_; }
  const PhysicsConfig& physics_config() const override { return config_; }
  const BulletConfig& config() const { return config_; }
  const RobotModel& model() const override { return *model_; }

 private:
  const Observation& advance(const ServoAction& action, bool braked);
  void apply_servo_torques(const ServoAction& action, bool braked);
  void read_observation();
  void measure(MeasuredJoints& joints, MeasuredBase& base) const;
  bool tire_touches_floor() const;

  std::shared_ptr<const RobotModel> model_;
  BulletConfig config_;
  RigidBodyTree tree_;
  std::unique_ptr<BulletWorld> world_;
  Observation observation_;
  SimulatedSensors sensors_;
  std::array<double, kNumServos> applied_torques_{};
  bool diverged_ = false;
};

}  // namespace upkie_rl
