#pragma once
/// @file
/// PhysicsSimulation: what the physics backends (Bullet, MuJoCo) add to Simulation, so that
/// the spine server and the benchmarks drive either one.

#include <memory>

#include "model/robot_model.hpp"
#include "sim/physics_config.hpp"
#include "sim/servo_law.hpp"
#include "sim/simulation.hpp"

namespace upkie_rl {

/// A simulation that integrates rigid-body physics with the servo law at each physics step.
class PhysicsSimulation : public Simulation {
 public:
  /// Maximum braking torque of stopped joints [N.m].
  static constexpr double kBrakeTorque = 100.0;

  /// Steps with every joint braked (velocity 0, up to kBrakeTorque), what a spine does
  /// to stopped servos.
  virtual const Observation& step_braked() = 0;

  /// Replaces the servo law gains kp and kd (the public Bullet spine takes them from each
  /// Start configuration); they apply from the next step.
  /// @throws std::invalid_argument when a gain is negative or not finite; nothing changes.
  void set_servo_gains(const ServoGains& gains);
  const ServoGains& servo_gains() const { return servo_gains_; }

  /// Settings it was built with.
  virtual const PhysicsConfig& physics_config() const = 0;
  virtual const RobotModel& model() const = 0;

  /// Physics steps taken since construction (for throughput measurements).
  long physics_steps() const { return physics_steps_; }

  double agent_timestep() const override { return physics_config().agent_timestep(); }

 protected:
  explicit PhysicsSimulation(const ServoGains& gains) : servo_gains_(gains) {}

  /// Servo torque of one joint for `command` (or the brake) at its measured state.
  double joint_torque(const ServoCommand& command, bool braked, double position, double velocity,
                      double effort) const;

  ServoGains servo_gains_;
  long physics_steps_ = 0;
};

}  // namespace upkie_rl
