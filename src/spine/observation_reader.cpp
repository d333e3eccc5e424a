#include "spine/observation_reader.hpp"

#include <string>
#include <string_view>

#include "spine/spine_error.hpp"

namespace upkie_rl {
namespace {

/// Key path for error messages, formatted only when throwing.
struct KeyPath {
  const KeyPath* parent;
  std::string_view key;
  std::string format() const {
    std::string text = parent != nullptr ? parent->format() + "." : std::string();
    text += key;
    return text;
  }
};

[[noreturn]] void fail(const KeyPath& path, std::string_view problem) {
  throw SpineError("spine observation key '" + path.format() + "' " + std::string(problem));
}

const msgpack::object* find(const msgpack::object& map, std::string_view key) {
  if (map.type != msgpack::type::MAP) return nullptr;
  for (std::uint32_t i = 0; i < map.via.map.size; ++i) {
    const msgpack::object& candidate = map.via.map.ptr[i].key;
    if (candidate.type == msgpack::type::STR &&
        std::string_view(candidate.via.str.ptr, candidate.via.str.size) == key) {
      return &map.via.map.ptr[i].val;
    }
  }
  return nullptr;
}

const msgpack::object& require(const msgpack::object& map, const KeyPath& path) {
  const msgpack::object* value = find(map, path.key);
  if (value == nullptr) fail(path, "is missing");
  return *value;
}

const msgpack::object& require_map(const msgpack::object& map, const KeyPath& path) {
  const msgpack::object& value = require(map, path);
  if (value.type != msgpack::type::MAP) fail(path, "is not a map");
  return value;
}

double number(const msgpack::object& value, const KeyPath& path) {
  switch (value.type) {
    case msgpack::type::FLOAT32:
    case msgpack::type::FLOAT64:
      return value.via.f64;
    case msgpack::type::POSITIVE_INTEGER:
      return static_cast<double>(value.via.u64);
    case msgpack::type::NEGATIVE_INTEGER:
      return static_cast<double>(value.via.i64);
    default:
      fail(path, "is not a number");
  }
}

/// Reads an array of exactly `size` numbers.
void numbers(const msgpack::object& value, const KeyPath& path, double* out, std::uint32_t size) {
  if (value.type != msgpack::type::ARRAY || value.via.array.size != size) {
    fail(path, "is not an array of " + std::to_string(size) + " numbers");
  }
  for (std::uint32_t i = 0; i < size; ++i) out[i] = number(value.via.array.ptr[i], path);
}

void read_number(const msgpack::object& map, const KeyPath& path, double& out, bool required) {
  const msgpack::object* value = find(map, path.key);
  if (value == nullptr) {
    if (required) fail(path, "is missing");
    return;
  }
  out = number(*value, path);
}

void read_vector3(const msgpack::object& map, const KeyPath& path, Eigen::Vector3d& out,
                  bool required) {
  const msgpack::object* value = find(map, path.key);
  if (value == nullptr) {
    if (required) fail(path, "is missing");
    return;
  }
  numbers(*value, path, out.data(), 3);
}

void read_quaternion(const msgpack::object& map, const KeyPath& path, Eigen::Quaterniond& out) {
  const msgpack::object* value = find(map, path.key);
  if (value == nullptr) return;
  double wxyz[4];
  numbers(*value, path, wxyz, 4);
  out = Eigen::Quaterniond(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
}

}  // namespace

void read_observation(const msgpack::object& message, Observation& observation) {
  if (message.type != msgpack::type::MAP) {
    throw SpineError("spine observation is not a map");
  }
  if (const msgpack::object* time = find(message, "time")) {
    observation.time = number(*time, {nullptr, "time"});
  }

  const KeyPath servo_path{nullptr, "servo"};
  const msgpack::object& servos = require_map(message, servo_path);
  for (std::size_t i = 0; i < kNumServos; ++i) {
    const KeyPath joint_path{&servo_path, kServoNames[i]};
    const msgpack::object& servo = require_map(servos, joint_path);
    ServoObservation& out = observation.servo[i];
    read_number(servo, {&joint_path, "position"}, out.position, true);
    read_number(servo, {&joint_path, "velocity"}, out.velocity, true);
    read_number(servo, {&joint_path, "torque"}, out.torque, true);
    read_number(servo, {&joint_path, "temperature"}, out.temperature, false);
    read_number(servo, {&joint_path, "voltage"}, out.voltage, false);
  }

  const KeyPath base_path{nullptr, "base_orientation"};
  const msgpack::object& base = require_map(message, base_path);
  auto& base_orientation = observation.base_orientation;
  read_number(base, {&base_path, "pitch"}, base_orientation.pitch, true);
  read_vector3(base, {&base_path, "angular_velocity"}, base_orientation.angular_velocity, true);
  const KeyPath rotation_path{&base_path, "rotation_base_to_world"};
  if (const msgpack::object* rotation = find(base, rotation_path.key)) {
    double row_major[9];
    numbers(*rotation, rotation_path, row_major, 9);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j)
        base_orientation.rotation_base_to_world(i, j) = row_major[3 * i + j];
    }
  }

  const KeyPath odometry_path{nullptr, "wheel_odometry"};
  const msgpack::object& odometry = require_map(message, odometry_path);
  read_number(odometry, {&odometry_path, "position"}, observation.wheel_odometry.position, true);
  read_number(odometry, {&odometry_path, "velocity"}, observation.wheel_odometry.velocity, true);

  const KeyPath imu_path{nullptr, "imu"};
  if (const msgpack::object* imu = find(message, imu_path.key)) {
    read_quaternion(*imu, {&imu_path, "orientation"}, observation.imu.orientation);
    read_vector3(*imu, {&imu_path, "angular_velocity"}, observation.imu.angular_velocity, false);
    read_vector3(*imu, {&imu_path, "linear_acceleration"}, observation.imu.linear_acceleration,
                 false);
    read_vector3(*imu, {&imu_path, "raw_linear_acceleration"},
                 observation.imu.raw_linear_acceleration, false);
  }

  const KeyPath contact_path{nullptr, "floor_contact"};
  if (const msgpack::object* floor_contact = find(message, contact_path.key)) {
    if (const msgpack::object* contact = find(*floor_contact, "contact")) {
      if (contact->type != msgpack::type::BOOLEAN) {
        fail({&contact_path, "contact"}, "is not a bool");
      }
      observation.floor_contact.contact = contact->via.boolean;
    }
  }

  observation.has_sim = false;
  const KeyPath sim_path{nullptr, "sim"};
  if (const msgpack::object* sim = find(message, sim_path.key)) {
    const KeyPath sim_base_path{&sim_path, "base"};
    if (const msgpack::object* sim_base = find(*sim, sim_base_path.key)) {
      auto& out = observation.sim_base;
      read_vector3(*sim_base, {&sim_base_path, "position"}, out.position, true);
      read_quaternion(*sim_base, {&sim_base_path, "orientation"}, out.orientation);
      read_vector3(*sim_base, {&sim_base_path, "linear_velocity"}, out.linear_velocity, false);
      read_vector3(*sim_base, {&sim_base_path, "angular_velocity"}, out.angular_velocity, false);
      observation.has_sim = true;
    }
  }
}

}  // namespace upkie_rl
