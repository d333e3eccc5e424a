#pragma once
/// @file
/// MujocoSimulation: Upkie in MuJoCo, behind the same interface and servo law as Bullet.

#include <memory>

#include "model/robot_model.hpp"
#include "sim/mujoco_config.hpp"
#include "sim/mujoco_model.hpp"
#include "sim/physics_simulation.hpp"

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

  RobotMassDistribution mass_distribution() const override;

  const PhysicsConfig& physics_config() const override { return config_; }
  const MujocoConfig& config() const { return config_; }
  const RobotModel& model() const override { return *model_; }
  const MujocoModel& mujoco_model() const { return *compiled_; }

 private:
  /// Points episode_model_ at the shared model, or at the simulation's own copy given the
  /// masses, payload and floor friction of variation() and `gravity` (always the copy with
  /// implicit wheel damping, whose damping changes with the servo commands).
  void apply_model_variation(const Eigen::Vector3d& gravity);
  /// The torque of each servo for `action` into qfrc_applied; with implicit wheel damping,
  /// the wheels' damping term moved into the own model's dof_damping.
  void apply_servo_torques(const ServoAction& action, bool braked);
  /// The tires' rolling resistance (MujocoConfig::tire_rolling_resistance) into
  /// xfrc_applied, from the contact forces of the last step.
  void apply_rolling_resistance();

  void step_physics(const ServoAction& action, bool braked) override;
  void measure(MeasuredJoints& joints, MeasuredBase& base) const override;
  bool tire_touches_floor() const override;
  bool non_tire_touches_floor() const override;

  std::shared_ptr<const RobotModel> model_;
  MujocoConfig config_;
  std::shared_ptr<const MujocoModel> compiled_;
  /// Made at the first reset with a model variation, or at construction with implicit
  /// wheel damping.
  MujocoModelPtr varied_model_;
  bool holds_variation_ = false;  ///< varied_model_ differs from the nominal one in masses.
  const mjModel_* episode_model_ = nullptr;
  MujocoDataPtr data_;
};

}  // namespace upkie_rl
