#pragma once
/// @file
/// BulletSimulation: Upkie in a Bullet (double precision, Featherstone btMultiBody) world
/// set up like the reference PyBullet simulation.

#include <memory>

#include "model/rigid_body_tree.hpp"
#include "model/robot_model.hpp"
#include "sim/bullet_config.hpp"
#include "sim/physics_simulation.hpp"

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

  RobotMassDistribution mass_distribution() const override;

  const PhysicsConfig& physics_config() const override { return config_; }
  const BulletConfig& config() const { return config_; }
  const RobotModel& model() const override { return *model_; }

 private:
  void step_physics(const ServoAction& action, bool braked) override;
  void measure(MeasuredJoints& joints, MeasuredBase& base) const override;
  bool tire_touches_floor() const override;
  bool non_tire_touches_floor() const override;
  /// Whether a tire (`tires`) or another robot part (`!tires`) is within 1 mm of the floor
  /// or a bump on it.
  bool floor_contact(bool tires) const;

  std::shared_ptr<const RobotModel> model_;
  BulletConfig config_;
  RigidBodyTree tree_;
  std::unique_ptr<BulletWorld> world_;
};

}  // namespace upkie_rl
