#pragma once
/// @file
/// PhysicsSimulation: what the physics backends (Bullet, MuJoCo) add to Simulation, so that
/// the spine server and the benchmarks drive either one.

#include <memory>
#include <random>

#include "model/robot_model.hpp"
#include "sim/floor_slope.hpp"
#include "sim/mass_properties.hpp"
#include "sim/measured_state.hpp"
#include "sim/physics_config.hpp"
#include "sim/physics_variation.hpp"
#include "sim/servo_law.hpp"
#include "sim/simulated_sensors.hpp"
#include "sim/simulation.hpp"

namespace upkie_rl {

/// How the robot's mass is distributed, as an engine simulates it (variation included).
struct RobotMassDistribution {
  double total_mass = 0.0;                                   ///< Whole robot [kg].
  Eigen::Vector3d center_of_mass = Eigen::Vector3d::Zero();  ///< Whole robot, world [m].
  /// The base body (the base link and every link welded to it), in the base link frame.
  MassProperties base;
};

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
  /// The gains servo `servo` applies: servo_gains() times the variation's servo_gain_scale.
  ServoGains servo_gains(std::size_t servo) const {
    const double scale = variation_.servo_gain_scale[servo];
    return {servo_gains_.kp * scale, servo_gains_.kd * scale};
  }

  /// Sets what differs from the nominal robot and world (masses, frictions, noise) in the
  /// episodes that the next resets start.
  /// @throws std::invalid_argument on a value out of its domain; nothing changes.
  void set_variation(const PhysicsVariation& variation);
  const PhysicsVariation& variation() const { return variation_; }

  /// Applies `force_in_world` [N] to the base's centre of mass at every physics step, until
  /// it is replaced or the simulation is reset (a push is a force held for a while).
  /// @throws std::invalid_argument on a non-finite force; nothing changes.
  void set_base_force(const Eigen::Vector3d& force_in_world);
  const Eigen::Vector3d& base_force() const { return base_force_; }

  /// The floor slope of the current episode (see start_floor_slope).
  const FloorSlope& floor_slope() const { return floor_slope_; }

  /// The robot's mass, centre of mass and base body as the engine has them now, in its
  /// world frame (the floor's): what the episode's variation made of the model.
  virtual RobotMassDistribution mass_distribution() const = 0;

  /// Settings it was built with.
  virtual const PhysicsConfig& physics_config() const = 0;
  virtual const RobotModel& model() const = 0;

  /// Physics steps taken since construction (for throughput measurements).
  long physics_steps() const { return physics_steps_; }

  double agent_timestep() const override { return physics_config().agent_timestep(); }

 protected:
  /// @throws std::invalid_argument on a setting out of its domain.
  PhysicsSimulation(const RobotModel& model, const PhysicsConfig& config);

  /// The torque limit of `servo` in this episode [N.m]: its effort times the variation's
  /// torque_limit_scale.
  double torque_limit(std::size_t servo) const {
    return model().servo_limits(servo).effort * variation_.torque_limit_scale;
  }

  /// Torque on joint `servo` in this physics step: the servo law of `command` (or the brake)
  /// at the measured state plus the episode's torque-control noise, which is what the
  /// servo applies and reports (recorded in applied_torques_), plus the joint's friction.
  double joint_torque(std::size_t servo, const ServoCommand& command, bool braked, double position,
                      double velocity);

  /// One physics step with the servo law of `action` (or the brake), through joint_torque,
  /// and base_force() on the base.
  virtual void step_physics(const ServoAction& action, bool braked) = 0;
  /// Joint and base state as the engine has it now.
  virtual void measure(MeasuredJoints& joints, MeasuredBase& base) const = 0;
  /// Whether a tire is within 1 mm of the floor.
  virtual bool tire_touches_floor() const = 0;
  /// Whether a part other than a tire touches the floor (floor_contact.non_wheel).
  virtual bool non_tire_touches_floor() const = 0;

  /// Starts the floor slope of variation() for the episode that `state` starts: tilted
  /// about the heading of its base, and the one the observers measure against until the
  /// next reset. Engines call it in their reset, before they set the episode's gravity.
  /// @return Gravity in the engine's world frame [m/s^2]: exactly (0, 0, -g) on a flat floor.
  const Eigen::Vector3d& start_floor_slope(const ResetState& state);

  /// Ends an engine's reset (which builds the variation() into its model): clears the base
  /// force, seeds the episode's noise and observes the state it set, at time 0.
  const Observation& observe_reset();

  std::array<double, kNumServos> applied_torques_{};  ///< Of the last physics step [N.m].

 private:
  const Observation& advance(const ServoAction& action, bool braked);

  ServoGains servo_gains_;
  PhysicsVariation variation_;
  Eigen::Vector3d base_force_ = Eigen::Vector3d::Zero();
  FloorSlope floor_slope_;
  std::mt19937_64 torque_noise_{0};
  SimulatedSensors sensors_;
  Observation observation_;
  long physics_steps_ = 0;
  bool diverged_ = false;
};

}  // namespace upkie_rl
