#pragma once
/// @file
/// PhysicsSimulation: what the physics backends (Bullet, MuJoCo) add to Simulation, so that
/// the spine server and the benchmarks drive either one.

#include <memory>

#include "model/robot_model.hpp"
#include "sim/measured_state.hpp"
#include "sim/physics_config.hpp"
#include "sim/servo_law.hpp"
#include "sim/simulated_sensors.hpp"
#include "sim/simulation.hpp"

namespace upkie_rl {

/// A simulation that integrates rigid-body physics with the servo law at each physics step.
/// The agent step is the same for every engine: it holds the commands for nb_substeps
/// physics steps, re-evaluating the servo law at each one with the joint state of that
/// step, then runs the shared observers (SimulatedSensors) on what the engine measures.
/// An engine implements one physics step, its measurements and its reset.
class PhysicsSimulation : public Simulation {
 public:
  /// Maximum braking torque of stopped joints [N.m].
  static constexpr double kBrakeTorque = 100.0;

  /// @throws InvalidCommandError on non-finite commands (see validate_servo_action).
  /// @throws SimulationDivergedError when the state becomes non-finite; reset to go on.
  const Observation& step(const ServoAction& action) final;

  /// Steps with every joint braked (velocity 0, up to kBrakeTorque), what a spine does
  /// to stopped servos.
  const Observation& step_braked();

  const Observation& observation() const final { return observation_; }

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
  /// @throws std::invalid_argument on a setting out of its domain.
  PhysicsSimulation(const RobotModel& model, const PhysicsConfig& config);

  /// Servo torque of one joint for `command` (or the brake) at its measured state.
  double joint_torque(const ServoCommand& command, bool braked, double position, double velocity,
                      double effort) const;

  /// One physics step with the servo law of `action` (or the brake); records the applied
  /// torques in applied_torques_.
  virtual void step_physics(const ServoAction& action, bool braked) = 0;
  /// Joint and base state as the engine has it now.
  virtual void measure(MeasuredJoints& joints, MeasuredBase& base) const = 0;
  /// Whether a tire is within 1 mm of the floor.
  virtual bool tire_touches_floor() const = 0;

  /// Ends an engine's reset: observes the state it set, at time 0.
  const Observation& observe_reset();

  std::array<double, kNumServos> applied_torques_{};  ///< Of the last physics step [N.m].

 private:
  const Observation& advance(const ServoAction& action, bool braked);

  ServoGains servo_gains_;
  SimulatedSensors sensors_;
  Observation observation_;
  long physics_steps_ = 0;
  bool diverged_ = false;
};

}  // namespace upkie_rl
