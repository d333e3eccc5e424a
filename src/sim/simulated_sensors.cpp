#include "sim/simulated_sensors.hpp"

#include <cmath>
#include <string>

#include "sim/base_observer.hpp"
#include "sim/simulation.hpp"

namespace upkie_rl {
namespace {

void check_finite(const MeasuredJoints& joints, const MeasuredBase& base, double time) {
  bool finite = base.pose_in_world.matrix().allFinite() &&
                base.linear_velocity_in_world.allFinite() &&
                base.angular_velocity_in_world.allFinite();
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    finite =
        finite && std::isfinite(joints.position[servo]) && std::isfinite(joints.velocity[servo]);
  }
  if (!finite) {
    throw SimulationDivergedError("the simulated state became non-finite at t = " +
                                  std::to_string(time) + " s; reset the simulation");
  }
}

}  // namespace

SimulatedSensors::SimulatedSensors(const RobotModel& model, const PhysicsConfig& config)
    : imu_(model, config.agent_timestep(), config.gravity), odometry_(model) {}

void SimulatedSensors::observe_without_imu(const MeasuredJoints& joints, const MeasuredBase& base,
                                           const MeasuredBase& level, bool floor_contact,
                                           Observation& observation) const {
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    ServoObservation& measured = observation.servo[servo];
    measured.position = joints.position[servo];
    measured.velocity = joints.velocity[servo];
    measured.torque = joints.torque[servo];
    measured.temperature = kTemperature;
    measured.voltage = kVoltage;
  }
  observation.has_sim = true;
  observe_base(base, observation.sim_base, observation.base_orientation);
  if (slope_.tilted) observe_attitude(level, observation.base_orientation);
  odometry_.observe(observation.servo, observation.wheel_odometry);
  observation.floor_contact.contact = floor_contact;
}

void SimulatedSensors::reset(const MeasuredJoints& joints, const MeasuredBase& base,
                             bool floor_contact, Observation& observation) {
  check_finite(joints, base, 0.0);
  observation = Observation{};
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    observation.servo[servo].position = joints.position[servo];
  }
  odometry_.reset(observation.servo);
  MeasuredBase scratch;
  const MeasuredBase& level = level_base(base, scratch);
  observe_without_imu(joints, base, level, floor_contact, observation);
  imu_.reset(level, observation.imu);
  add_imu_uncertainty(observation);
}

void SimulatedSensors::set_imu_uncertainty(const ImuUncertainty& uncertainty,
                                           std::uint64_t noise_seed) {
  uncertainty.validate();
  imu_uncertainty_ = uncertainty;
  imu_noise_.seed(noise_seed);
}

const MeasuredBase& SimulatedSensors::level_base(const MeasuredBase& base,
                                                 MeasuredBase& scratch) const {
  if (!slope_.tilted) return base;
  const Eigen::Matrix3d& rotation = slope_.rotation_floor_to_level;
  scratch.pose_in_world.linear() = rotation * base.pose_in_world.linear();
  scratch.pose_in_world.translation() = rotation * base.pose_in_world.translation();
  scratch.linear_velocity_in_world = rotation * base.linear_velocity_in_world;
  scratch.angular_velocity_in_world = rotation * base.angular_velocity_in_world;
  return scratch;
}

void SimulatedSensors::add_imu_uncertainty(Observation& observation) {
  // The pitch rate of base_orientation comes from the gyroscope, so it carries its error.
  if (!imu_uncertainty_.is_zero()) {
    observation.base_orientation.angular_velocity +=
        imu_.add_uncertainty(imu_uncertainty_, imu_noise_, observation.imu);
  }
}

void SimulatedSensors::observe(const MeasuredJoints& joints, const MeasuredBase& base,
                               bool floor_contact, Observation& observation) {
  check_finite(joints, base, observation.time);
  MeasuredBase scratch;
  const MeasuredBase& level = level_base(base, scratch);
  observe_without_imu(joints, base, level, floor_contact, observation);
  imu_.observe(level, observation.imu);
  add_imu_uncertainty(observation);
}

}  // namespace upkie_rl
