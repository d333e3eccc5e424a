#pragma once
/// @file
/// The one walk over an Observation's nested-dictionary view (the Upkie spine's keys), shared
/// by every writer of that view.

#include <cmath>
#include <cstddef>

#include "sim/observation.hpp"
#include "sim/observation_dict.hpp"

namespace upkie_rl {

namespace detail {

template <typename Writer>
void walk_wheel_contact(const Observation& observation, std::size_t wheel, Writer& writer) {
  writer.begin_map(4);
  writer.key("abs_acceleration");
  writer.real(0.0);
  writer.key("abs_torque");
  writer.real(std::abs(observation.servo[wheel].torque));
  writer.key("contact");
  writer.boolean(observation.floor_contact.contact);
  writer.key("inertia");
  writer.real(0.0);
  writer.end_map();
}

template <typename Writer>
void walk_vector3(const Eigen::Vector3d& vector, Writer& writer) {
  writer.reals(vector.data(), 3);
}

template <typename Writer>
void walk_quaternion(const Eigen::Quaterniond& quaternion, Writer& writer) {
  const double wxyz[4] = {quaternion.w(), quaternion.x(), quaternion.y(), quaternion.z()};
  writer.reals(wxyz, 4);
}

}  // namespace detail

/// Walks the observation tree once, in sorted key order, calling `writer`: begin_map(size),
/// end_map(), key(string_view), real(double), boolean(bool), integer(int),
/// reals(const double*, size). Every dictionary view (JSON, msgpack, Python) comes from
/// this one walk, so they cannot disagree; the keys and simulated values are documented in
/// sim/observation_dict.hpp.
template <typename Writer>
void walk_observation(const Observation& observation, Writer& writer) {
  using detail::walk_quaternion;
  using detail::walk_vector3;
  using detail::walk_wheel_contact;
  writer.begin_map(observation.has_sim ? 7 : 6);

  const auto& base_orientation = observation.base_orientation;
  writer.key("base_orientation");
  writer.begin_map(3);
  writer.key("angular_velocity");
  walk_vector3(base_orientation.angular_velocity, writer);
  writer.key("pitch");
  writer.real(base_orientation.pitch);
  writer.key("rotation_base_to_world");
  double row_major[9];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      row_major[3 * i + j] = base_orientation.rotation_base_to_world(i, j);
    }
  }
  writer.reals(row_major, 9);
  writer.end_map();

  writer.key("floor_contact");
  writer.begin_map(4);
  writer.key("contact");
  writer.boolean(observation.floor_contact.contact);
  writer.key("left_wheel");
  walk_wheel_contact(observation, kLeftWheel, writer);
  writer.key("right_wheel");
  walk_wheel_contact(observation, kRightWheel, writer);
  writer.key("upper_leg_torque");
  double squared_torques = 0.0;
  for (std::size_t servo : {kLeftHip, kLeftKnee, kRightHip, kRightKnee}) {
    squared_torques += observation.servo[servo].torque * observation.servo[servo].torque;
  }
  writer.real(std::sqrt(squared_torques));
  writer.end_map();

  const auto& imu = observation.imu;
  writer.key("imu");
  writer.begin_map(5);
  writer.key("angular_velocity");
  walk_vector3(imu.angular_velocity, writer);
  writer.key("linear_acceleration");
  walk_vector3(imu.linear_acceleration, writer);
  writer.key("orientation");
  walk_quaternion(imu.orientation, writer);
  writer.key("raw_angular_velocity");
  walk_vector3(imu.angular_velocity, writer);
  writer.key("raw_linear_acceleration");
  walk_vector3(imu.raw_linear_acceleration, writer);
  writer.end_map();

  // kServoNames is already in sorted order (left_* before right_*, hip < knee < wheel).
  writer.key("servo");
  writer.begin_map(kNumServos);
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    const ServoObservation& measured = observation.servo[servo];
    writer.key(kServoNames[servo]);
    writer.begin_map(9);
    writer.key("d_current");
    writer.real(0.0);
    writer.key("fault");
    writer.integer(0);
    writer.key("mode");
    writer.integer(kServoModePosition);
    writer.key("position");
    writer.real(measured.position);
    writer.key("q_current");
    writer.real(0.0);
    writer.key("temperature");
    writer.real(measured.temperature);
    writer.key("torque");
    writer.real(measured.torque);
    writer.key("velocity");
    writer.real(measured.velocity);
    writer.key("voltage");
    writer.real(measured.voltage);
    writer.end_map();
  }
  writer.end_map();

  if (observation.has_sim) {
    const auto& base = observation.sim_base;
    writer.key("sim");
    writer.begin_map(2);
    writer.key("base");
    writer.begin_map(4);
    writer.key("angular_velocity");
    walk_vector3(base.angular_velocity, writer);
    writer.key("linear_velocity");
    walk_vector3(base.linear_velocity, writer);
    writer.key("orientation");
    walk_quaternion(base.orientation, writer);
    writer.key("position");
    walk_vector3(base.position, writer);
    writer.end_map();
    writer.key("imu");
    writer.begin_map(1);
    writer.key("linear_velocity");
    walk_vector3(base.linear_velocity, writer);
    writer.end_map();
    writer.end_map();
  }

  writer.key("time");
  writer.real(observation.time);

  writer.key("wheel_odometry");
  writer.begin_map(2);
  writer.key("position");
  writer.real(observation.wheel_odometry.position);
  writer.key("velocity");
  writer.real(observation.wheel_odometry.velocity);
  writer.end_map();

  writer.end_map();
}

}  // namespace upkie_rl
