#pragma once
/// @file
/// The observation dictionary (the Upkie spine's keys, docs/spine.md) declared once: which
/// key holds which field of an Observation, in which map, and whether a reader needs it.
/// The writers (msgpack for the spine link, JSON for logs, Python dicts) and the spine's
/// reader all walk this one declaration, so a key added here reaches every one of them.
///
/// The declaration calls a visitor, in the byte-wise sorted key order of every map (the
/// order of the spine's msgpack maps):
/// - `map(key, presence, children)`: a nested map; `children(visitor)` declares its keys;
/// - `map_if(key, flag, children)`: a map written only when `flag` is true; a reader sets
///   `flag` to whether the key is there;
/// - `real`, `boolean`, `vector3`, `quaternion` ([w, x, y, z]), `matrix3` (9 numbers,
///   row-major), each `(key, field, presence)`: a field of the Observation, a reference to
///   a const member for writers and to a mutable one for readers;
/// - `computed(key, value)`: a value the spine writes that the typed Observation does not
///   carry (see sim/observation_dict.hpp); `value()` returns a double, an int, a bool or a
///   vector, and only writers call it; readers skip the key.
///
/// Keys are string literals or joint names (std::string_view of static storage), so a walk
/// builds no string and allocates nothing of its own.

#include <cmath>
#include <cstddef>
#include <string_view>

#include "sim/observation.hpp"
#include "sim/servo_command_fields.hpp"

namespace upkie_rl {

/// One measured field of a ServoObservation and its key (`servo.<joint>.<key>` in the
/// spine's dictionary, `<joint>.<key>` in the servos environment's flat observation).
struct ServoObservationField {
  std::string_view key;
  double ServoObservation::*member;
  /// A spine observation without this key is refused (the others keep their value).
  bool required;
};

/// The measured fields of a ServoObservation, declared once, in the servos environment's
/// flat order; the observation dictionary (below) takes its servo
/// measurements from this table.
inline constexpr std::array<ServoObservationField, 5> kServoObservationFields = {{
    {"position", &ServoObservation::position, true},
    {"velocity", &ServoObservation::velocity, true},
    {"torque", &ServoObservation::torque, true},
    {"temperature", &ServoObservation::temperature, false},
    {"voltage", &ServoObservation::voltage, false},
}};

/// moteus' mode number for position control, written as `servo.<joint>.mode`.
inline constexpr int kServoModePosition = 10;

/// Whether a reader of the dictionary refuses a message without the key. An optional key
/// that is absent leaves its field as it was.
enum class KeyPresence { kRequired, kOptional };

/// The entry of kServoObservationFields that holds `member` (a compile-time lookup, so the
/// declaration below names fields, not keys).
constexpr const ServoObservationField& servo_observation_field(double ServoObservation::*member) {
  for (const ServoObservationField& field : kServoObservationFields) {
    if (field.member == member) return field;
  }
  throw "not a field of kServoObservationFields";  // a compile error in constant evaluation
}

namespace observation_fields {

template <typename Servo, typename Visitor>
void visit_measured(Servo& servo, double ServoObservation::*member, Visitor& visitor) {
  const ServoObservationField& field = servo_observation_field(member);
  visitor.real(field.key, servo.*field.member,
               field.required ? KeyPresence::kRequired : KeyPresence::kOptional);
}

/// `servo.<joint>`: the measured fields of kServoObservationFields among the simulated ones.
template <typename Servo, typename Visitor>
void visit_servo(Servo& servo, Visitor& visitor) {
  visitor.computed("d_current", [] { return 0.0; });
  visitor.computed("fault", [] { return 0; });
  visitor.computed("mode", [] { return kServoModePosition; });
  visit_measured(servo, &ServoObservation::position, visitor);
  visitor.computed("q_current", [] { return 0.0; });
  visit_measured(servo, &ServoObservation::temperature, visitor);
  visit_measured(servo, &ServoObservation::torque, visitor);
  visit_measured(servo, &ServoObservation::velocity, visitor);
  visit_measured(servo, &ServoObservation::voltage, visitor);
}

template <typename ObservationT, typename Visitor>
void visit_servos(ObservationT& observation, Visitor& visitor) {
  visitor.map(kServoMapKey, KeyPresence::kRequired, [&](auto& servos) {
    for (std::size_t servo = 0; servo < kNumServos; ++servo) {
      // kServoNames is already in sorted order (left_* before right_*, hip < knee < wheel).
      servos.map(kServoNames[servo], KeyPresence::kRequired,
                 [&](auto& fields) { visit_servo(observation.servo[servo], fields); });
    }
  });
}

template <typename ObservationT, typename Visitor>
void visit_base_orientation(ObservationT& observation, Visitor& visitor) {
  auto& base_orientation = observation.base_orientation;
  visitor.map("base_orientation", KeyPresence::kRequired, [&](auto& fields) {
    fields.vector3("angular_velocity", base_orientation.angular_velocity, KeyPresence::kRequired);
    fields.real("pitch", base_orientation.pitch, KeyPresence::kRequired);
    fields.matrix3("rotation_base_to_world", base_orientation.rotation_base_to_world,
                   KeyPresence::kOptional);
  });
}

/// `floor_contact.<wheel>`: the real observer's filters are not simulated.
template <typename ObservationT, typename Visitor>
void visit_wheel_contact(ObservationT& observation, std::size_t wheel, Visitor& visitor) {
  visitor.map(kServoNames[wheel], KeyPresence::kOptional, [&](auto& fields) {
    fields.computed("abs_acceleration", [] { return 0.0; });
    fields.computed("abs_torque", [&] { return std::abs(observation.servo[wheel].torque); });
    fields.computed("contact",
                    [&] { return static_cast<bool>(observation.floor_contact.contact); });
    fields.computed("inertia", [] { return 0.0; });
  });
}

template <typename ObservationT, typename Visitor>
void visit_floor_contact(ObservationT& observation, Visitor& visitor) {
  visitor.map("floor_contact", KeyPresence::kOptional, [&](auto& fields) {
    fields.boolean("contact", observation.floor_contact.contact, KeyPresence::kOptional);
    visit_wheel_contact(observation, kLeftWheel, fields);
    visit_wheel_contact(observation, kRightWheel, fields);
    fields.computed("upper_leg_torque", [&] {
      double squared_torques = 0.0;
      for (std::size_t servo : {kLeftHip, kLeftKnee, kRightHip, kRightKnee}) {
        squared_torques += observation.servo[servo].torque * observation.servo[servo].torque;
      }
      return std::sqrt(squared_torques);
    });
  });
}

template <typename ObservationT, typename Visitor>
void visit_imu(ObservationT& observation, Visitor& visitor) {
  auto& imu = observation.imu;
  visitor.map("imu", KeyPresence::kOptional, [&](auto& fields) {
    fields.vector3("angular_velocity", imu.angular_velocity, KeyPresence::kOptional);
    fields.vector3("linear_acceleration", imu.linear_acceleration, KeyPresence::kOptional);
    fields.quaternion("orientation", imu.orientation, KeyPresence::kOptional);
    // No gyro bias is simulated: the raw angular velocity is the filtered one.
    fields.computed("raw_angular_velocity",
                    [&]() -> const Eigen::Vector3d& { return imu.angular_velocity; });
    fields.vector3("raw_linear_acceleration", imu.raw_linear_acceleration, KeyPresence::kOptional);
  });
}

/// `sim`: ground truth, written when has_sim is true; a reader sets has_sim when it is there.
template <typename ObservationT, typename Visitor>
void visit_sim(ObservationT& observation, Visitor& visitor) {
  auto& base = observation.sim_base;
  visitor.map_if("sim", observation.has_sim, [&](auto& sim) {
    sim.map("base", KeyPresence::kRequired, [&](auto& fields) {
      fields.vector3("angular_velocity", base.angular_velocity, KeyPresence::kOptional);
      fields.vector3("linear_velocity", base.linear_velocity, KeyPresence::kOptional);
      fields.quaternion("orientation", base.orientation, KeyPresence::kOptional);
      fields.vector3("position", base.position, KeyPresence::kRequired);
    });
    sim.map("imu", KeyPresence::kOptional, [&](auto& fields) {
      // The base origin's velocity: the IMU is 0.1 m from it (off by |omega x r|).
      fields.computed("linear_velocity",
                      [&]() -> const Eigen::Vector3d& { return base.linear_velocity; });
    });
  });
}

template <typename ObservationT, typename Visitor>
void visit_wheel_odometry(ObservationT& observation, Visitor& visitor) {
  auto& odometry = observation.wheel_odometry;
  visitor.map("wheel_odometry", KeyPresence::kRequired, [&](auto& fields) {
    fields.real("position", odometry.position, KeyPresence::kRequired);
    fields.real("velocity", odometry.velocity, KeyPresence::kRequired);
  });
}

}  // namespace observation_fields

/// Declares every key of the observation dictionary to `visitor` (see the file comment),
/// top-level keys in sorted order. `ObservationT` is `const Observation` for a writer and
/// `Observation` for a reader.
template <typename ObservationT, typename Visitor>
void visit_observation_fields(ObservationT& observation, Visitor& visitor) {
  observation_fields::visit_base_orientation(observation, visitor);
  observation_fields::visit_floor_contact(observation, visitor);
  observation_fields::visit_imu(observation, visitor);
  observation_fields::visit_servos(observation, visitor);
  observation_fields::visit_sim(observation, visitor);
  visitor.real("time", observation.time, KeyPresence::kOptional);
  observation_fields::visit_wheel_odometry(observation, visitor);
}

}  // namespace upkie_rl
