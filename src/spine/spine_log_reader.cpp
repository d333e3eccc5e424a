#include "spine/spine_log_reader.hpp"

#include <cmath>
#include <msgpack.hpp>

#include "base/input_file.hpp"
#include "model/joint_order.hpp"
#include "sim/servo_command_fields.hpp"
#include "spine/dictionary.hpp"
#include "spine/observation_reader.hpp"
#include "spine/servo_action_message.hpp"

namespace upkie_rl {

namespace {

/// Limits on one dictionary: a spine's cycle dictionary has a few dozen keys per map.
msgpack::unpack_limit spine_log_limits() {
  constexpr std::size_t kMaxContainer = 4096;
  constexpr std::size_t kMaxString = std::size_t{1} << 20;
  return msgpack::unpack_limit(kMaxContainer, kMaxContainer, kMaxString, kMaxString, kMaxString,
                               32);
}

/// The value of `key` in the map `map`, or nullptr.
const msgpack::object* find_key(const msgpack::object& map, std::string_view key) {
  for (std::uint32_t i = 0; i < map.via.map.size; ++i) {
    const msgpack::object_kv& pair = map.via.map.ptr[i];
    if (pair.key.type == msgpack::type::STR &&
        std::string_view(pair.key.via.str.ptr, pair.key.via.str.size) == key) {
      return &pair.val;
    }
  }
  return nullptr;
}

/// Checks the measurements identification and replay rely on.
void check_measurements(const LoggedCycle& cycle, const std::string& where) {
  check_logged_value(cycle.time, kSpineLogTimeKey, where);
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    const ServoObservation& measured = cycle.observation.servo[servo];
    const std::string prefix = "servo." + std::string(kServoNames[servo]) + ".";
    check_logged_value(measured.position, prefix + "position", where);
    check_logged_value(measured.velocity, prefix + "velocity", where);
    check_logged_value(measured.torque, prefix + "torque", where);
  }
  const BaseOrientationObservation& base = cycle.observation.base_orientation;
  check_logged_value(base.pitch, "base_orientation.pitch", where);
  for (int axis = 0; axis < 3; ++axis) {
    check_logged_value(base.angular_velocity[axis], "base_orientation.angular_velocity", where);
    for (int column = 0; column < 3; ++column) {
      check_logged_value(base.rotation_base_to_world(axis, column),
                         "base_orientation.rotation_base_to_world", where);
    }
  }
  check_logged_value(cycle.observation.wheel_odometry.position, "wheel_odometry.position", where);
  check_logged_value(cycle.observation.wheel_odometry.velocity, "wheel_odometry.velocity", where);
}

/// Commands may have a NaN position (no position loop) and an infinite maximum torque (no
/// clamp beyond the effort, in a simulation); everything else is a number (kServoCommandFields).
void check_commands(const ServoAction& action, const std::string& where) {
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    for (const ServoCommandField& field : kServoCommandFields) {
      const double value = action[servo].*field.member;
      if ((field.nan_allowed && std::isnan(value)) ||
          (field.positive_infinity_allowed && value == HUGE_VAL)) {
        continue;
      }
      check_logged_value(
          value, "action.servo." + std::string(kServoNames[servo]) + "." + std::string(field.key),
          where);
    }
  }
}

/// Reads one dictionary of the stream into `cycle`; false when it has no observation.
bool read_cycle(const msgpack::object& entry, Dictionary& action, LoggedCycle& cycle,
                const std::string& where) {
  if (entry.type != msgpack::type::MAP) {
    throw RobotLogError(where + "is not a dictionary; is this a spine log (mpacklog)?");
  }
  const msgpack::object* observation = find_key(entry, kSpineLogObservationKey);
  if (observation == nullptr) return false;
  try {
    read_observation(*observation, cycle.observation);
    if (const msgpack::object* action_entry = find_key(entry, kSpineLogActionKey)) {
      action.update(*action_entry);
      if (action.has("servo")) read_servo_action(action, cycle.command);
    }
  } catch (const Error& error) {
    throw RobotLogError(where + error.what());
  }
  const msgpack::object* time = find_key(entry, kSpineLogTimeKey);
  if (time != nullptr &&
      (time->type == msgpack::type::FLOAT64 || time->type == msgpack::type::FLOAT32)) {
    cycle.time = time->via.f64;
  } else {
    cycle.time = cycle.observation.time;
  }
  check_measurements(cycle, where);
  check_commands(cycle.command, where);
  return true;
}

}  // namespace

void check_logged_value(double value, std::string_view what, const std::string& where) {
  if (std::isnan(value)) throw RobotLogError(where + std::string(what) + " is NaN");
  if (!(std::abs(value) <= kMaxLoggedMagnitude)) {
    throw RobotLogError(where + std::string(what) + " is " + std::to_string(value) +
                        ", beyond any measurement (|value| > 1e6): a corrupt record");
  }
}

bool looks_like_spine_log(std::string_view bytes) {
  if (bytes.empty()) return false;
  const auto first = static_cast<unsigned char>(bytes.front());
  return (first >= 0x80 && first <= 0x8f) || first == 0xde || first == 0xdf;
}

std::vector<LoggedCycle> read_spine_log(const std::filesystem::path& path) {
  const std::string bytes = read_input_file<RobotLogError>(path, "spine log", kMaxSpineLogBytes);
  return read_spine_log(bytes, path.string());
}

std::vector<LoggedCycle> read_spine_log(std::string_view bytes, const std::string& name) {
  std::vector<LoggedCycle> cycles;
  Dictionary action;
  LoggedCycle cycle;
  cycle.command = spine_default_servo_action();
  std::size_t offset = 0;
  std::size_t index = 0;
  while (offset < bytes.size()) {
    const std::size_t start = offset;
    const std::string where = "spine log " + name + ": dictionary " + std::to_string(index) +
                              " (byte " + std::to_string(start) + "): ";
    msgpack::object_handle handle;
    try {
      handle =
          msgpack::unpack(bytes.data(), bytes.size(), offset, nullptr, nullptr, spine_log_limits());
    } catch (const msgpack::insufficient_bytes&) {
      throw RobotLogError(where + "truncated mpack stream, " +
                          std::to_string(bytes.size() - start) +
                          " bytes of an incomplete dictionary at the end (the writer stopped "
                          "mid-write?)");
    } catch (const std::exception& error) {
      throw RobotLogError(where + "malformed MessagePack (" + error.what() + ")");
    }
    if (read_cycle(handle.get(), action, cycle, where)) {
      if (!cycles.empty() && !(cycle.time > cycles.back().time)) {
        throw RobotLogError(where + "time " + std::to_string(cycle.time) +
                            " s does not increase (the previous cycle is at " +
                            std::to_string(cycles.back().time) + " s)");
      }
      cycles.push_back(cycle);
    }
    ++index;
  }
  if (cycles.size() < 2) {
    throw RobotLogError("spine log " + name + ": " + std::to_string(cycles.size()) +
                        " cycles with an observation, need at least 2");
  }
  return cycles;
}

}  // namespace upkie_rl
