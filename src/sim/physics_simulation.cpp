#include "sim/physics_simulation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/base_observer.hpp"
#include "sim/random_draws.hpp"

namespace upkie_rl {
namespace {

/// Joints slower than this feel no kinetic friction [rad/s] (public Upkie's threshold).
constexpr double kFrictionVelocityThreshold = 1e-3;

/// Noise streams of an episode, derived from PhysicsVariation::noise_seed.
enum NoiseStream : std::uint64_t { kTorqueNoise = 0, kImuNoise = 1 };

}  // namespace

PhysicsSimulation::PhysicsSimulation(const RobotModel& model, const PhysicsConfig& config)
    : servo_gains_(config.servo_gains),
      floor_slope_(make_floor_slope(0.0, 0.0, 0.0, config.gravity)),
      sensors_(model, config) {}

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
  if (variation_.torque_measurement_noise > 0.0) {
    for (double& torque : joints.torque) {
      torque += variation_.torque_measurement_noise * standard_normal(torque_noise_);
    }
  }
  try {
    sensors_.observe(joints, base, tire_touches_floor(), observation_);
    observation_.floor_contact.non_wheel = non_tire_touches_floor();
  } catch (const SimulationDivergedError&) {
    diverged_ = true;
    throw;
  }
  return observation_;
}

const Eigen::Vector3d& PhysicsSimulation::start_floor_slope(const ResetState& state) {
  const double heading = base_yaw(state.orientation_base_in_world.normalized().toRotationMatrix());
  floor_slope_ = make_floor_slope(variation_.slope_pitch, variation_.slope_roll, heading,
                                  physics_config().gravity);
  sensors_.set_floor_slope(floor_slope_);
  return floor_slope_.gravity_in_floor;
}

const Observation& PhysicsSimulation::observe_reset() {
  applied_torques_.fill(0.0);
  diverged_ = false;
  base_force_.setZero();
  torque_noise_.seed(derive_seed(variation_.noise_seed, kTorqueNoise));
  sensors_.set_imu_uncertainty(variation_.imu, derive_seed(variation_.noise_seed, kImuNoise));
  MeasuredJoints joints;
  MeasuredBase base;
  measure(joints, base);
  sensors_.reset(joints, base, tire_touches_floor(), observation_);
  observation_.floor_contact.non_wheel = non_tire_touches_floor();
  return observation_;
}

void PhysicsSimulation::set_servo_gains(const ServoGains& gains) {
  if (!is_valid_servo_gain(gains.kp) || !is_valid_servo_gain(gains.kd)) {
    throw std::invalid_argument("servo gains must be finite and non-negative, got kp " +
                                std::to_string(gains.kp) + " and kd " + std::to_string(gains.kd));
  }
  servo_gains_ = gains;
}

void PhysicsSimulation::set_variation(const PhysicsVariation& variation) {
  variation.validate();
  variation_ = variation;
}

void PhysicsSimulation::set_base_force(const Eigen::Vector3d& force_in_world) {
  if (!force_in_world.allFinite()) {
    throw std::invalid_argument("the force on the base must be finite");
  }
  base_force_ = force_in_world;
}

double PhysicsSimulation::joint_torque(std::size_t servo, const ServoCommand& command, bool braked,
                                       double position, double velocity) {
  const ServoGains gains = servo_gains(servo);
  double torque = braked ? std::clamp(-gains.kd * velocity, -kBrakeTorque, kBrakeTorque)
                         : servo_torque(command, position, velocity, gains, torque_limit(servo));
  if (variation_.torque_control_noise > 0.0) {
    torque += variation_.torque_control_noise * standard_normal(torque_noise_);
  }
  applied_torques_[servo] = torque;
  const double friction = variation_.joint_friction[servo];
  if (friction > 0.0 && std::abs(velocity) > kFrictionVelocityThreshold) {
    torque -= std::copysign(friction, velocity);
  }
  return torque;
}

}  // namespace upkie_rl
