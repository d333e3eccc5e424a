#include "sim/physics_simulation.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace upkie_rl {

PhysicsSimulation::PhysicsSimulation(const RobotModel& model, const PhysicsConfig& config)
    : servo_gains_(config.servo_gains), sensors_(model, config) {}

const Observation& PhysicsSimulation::step(const ServoAction& action) {
  validate_servo_action(action);
  return advance(action, /*braked=*/false);
}

const Observation& PhysicsSimulation::step_braked() {
  static const ServoAction kNoAction{};
  return advance(kNoAction, /*braked=*/true);
}

const Observation& PhysicsSimulation::advance(const ServoAction& action, bool braked) {
  if (diverged_) {
    throw SimulationDivergedError("the simulation diverged earlier; reset it before stepping");
  }
  const PhysicsConfig& config = physics_config();
  for (int substep = 0; substep < config.nb_substeps; ++substep) {
    step_physics(action, braked);
    ++physics_steps_;
  }
  observation_.time += config.agent_timestep();
  MeasuredJoints joints;
  MeasuredBase base;
  measure(joints, base);
  try {
    sensors_.observe(joints, base, tire_touches_floor(), observation_);
  } catch (const SimulationDivergedError&) {
    diverged_ = true;
    throw;
  }
  return observation_;
}

const Observation& PhysicsSimulation::observe_reset() {
  applied_torques_.fill(0.0);
  diverged_ = false;
  MeasuredJoints joints;
  MeasuredBase base;
  measure(joints, base);
  sensors_.reset(joints, base, tire_touches_floor(), observation_);
  return observation_;
}

void PhysicsSimulation::set_servo_gains(const ServoGains& gains) {
  if (!is_valid_servo_gain(gains.kp) || !is_valid_servo_gain(gains.kd)) {
    throw std::invalid_argument("servo gains must be finite and non-negative, got kp " +
                                std::to_string(gains.kp) + " and kd " + std::to_string(gains.kd));
  }
  servo_gains_ = gains;
}

double PhysicsSimulation::joint_torque(const ServoCommand& command, bool braked, double position,
                                       double velocity, double effort) const {
  if (braked) return std::clamp(-servo_gains_.kd * velocity, -kBrakeTorque, kBrakeTorque);
  return servo_torque(command, position, velocity, servo_gains_, effort);
}

}  // namespace upkie_rl
