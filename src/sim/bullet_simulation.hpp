#pragma once
/// @file
/// BulletSimulation: Upkie in a Bullet (double precision, Featherstone btMultiBody) world
/// set up like the reference PyBullet simulation.

#include <memory>

#include "model/rigid_body_tree.hpp"
#include "model/robot_model.hpp"
#include "sim/bullet_config.hpp"
#include "sim/servo_law.hpp"
#include "sim/simulation.hpp"

namespace upkie_rl {

struct BulletWorld;

/// One robot in its own Bullet world. Each agent step holds the servo commands for
/// `nb_substeps` physics steps, re-evaluating the servo law at every physics step with the
/// joint state measured at that step; the observation is read after the last one.
/// Not thread-safe; one instance per thread.
class BulletSimulation final : public Simulation {
 public:
  /// @param model  Robot description, shared and immutable.
  /// @throws std::invalid_argument on a non-positive timestep or substep count.
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

  /// Steps with every joint braked (velocity 0, up to kBrakeTorque), what a spine does
  /// to stopped servos.
  const Observation& step_braked();

  const Observation& observation() const override { return observation_; }
  double agent_timestep() const override { return config_.physics_timestep * config_.nb_substeps; }

  const BulletConfig& config() const { return config_; }

  /// Replaces the servo law gains kp and kd (the public Bullet spine takes them from each
  /// Start configuration); they apply from the next step.
  /// @throws std::invalid_argument when a gain is negative or not finite.
  void set_servo_gains(const ServoGains& gains);
  ServoGains servo_gains() const { return {config_.kp, config_.kd}; }
  const RobotModel& model() const { return *model_; }

  /// Physics steps taken since construction (for throughput measurements).
  long physics_steps() const { return physics_steps_; }

  /// Maximum braking torque of stopped joints [N.m].
  static constexpr double kBrakeTorque = 100.0;

 private:
  const Observation& advance(const ServoAction& action, bool braked);
  void apply_servo_torques(const ServoAction& action, bool braked);
  void read_observation();

  std::shared_ptr<const RobotModel> model_;
  BulletConfig config_;
  RigidBodyTree tree_;
  std::unique_ptr<BulletWorld> world_;
  Observation observation_;
  ResetState reset_state_;
  std::array<double, kNumServos> applied_torques_{};
  std::array<double, kNumServos> reset_joint_angles_{};
  Eigen::Vector3d previous_imu_velocity_ = Eigen::Vector3d::Zero();
  long physics_steps_ = 0;
  bool diverged_ = false;
};

}  // namespace upkie_rl
