#include "spine/servo_action_message.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <string_view>

#include "sim/msgpack_float64.hpp"
#include "sim/servo_command_fields.hpp"
#include "spine/spine_error.hpp"

namespace upkie_rl {
namespace {

void pack_key(msgpack::packer<msgpack::sbuffer>& packer, std::string_view key) {
  packer.pack_str(static_cast<std::uint32_t>(key.size()));
  packer.pack_str_body(key.data(), static_cast<std::uint32_t>(key.size()));
}

}  // namespace

void write_servo_action_msgpack(const ServoAction& action, msgpack::sbuffer& buffer) {
  buffer.clear();
  msgpack::packer<msgpack::sbuffer> packer(buffer);
  packer.pack_map(1);
  pack_key(packer, kServoMapKey);
  packer.pack_map(kNumServos);
  for (std::size_t i = 0; i < kNumServos; ++i) {
    const ServoCommand& command = action[i];
    pack_key(packer, kServoNames[i]);
    packer.pack_map(static_cast<std::uint32_t>(kServoCommandFieldsByKey.size()));
    for (const ServoCommandField& field : kServoCommandFieldsByKey) {
      pack_key(packer, field.key);
      pack_float64(buffer, command.*field.member);
    }
  }
}

ServoAction spine_default_servo_action() {
  ServoAction action;
  for (ServoCommand& command : action) {
    command = ServoCommand{std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0, 1.0, 1.0, 1.0};
  }
  return action;
}

void read_servo_action(const Dictionary& dictionary, ServoAction& action,
                       const std::array<double, kNumServos>* maximum_torques) {
  if (!dictionary.has(kServoMapKey)) return;
  const Dictionary& servos = dictionary.at(kServoMapKey);
  if (!servos.is_map()) throw SpineError("action key 'servo' is not a map");
  for (std::size_t i = 0; i < kNumServos; ++i) {
    if (!servos.has(kServoNames[i])) continue;
    const Dictionary& fields = servos.at(kServoNames[i]);
    ServoCommand& command = action[i];
    const auto read = [&](std::string_view key, double& out) {
      if (!fields.has(key)) return;
      const Dictionary& value = fields.at(key);
      if (value.kind() != Dictionary::Kind::kFloat && value.kind() != Dictionary::Kind::kInt) {
        throw SpineError("action key 'servo." + std::string(kServoNames[i]) + "." +
                         std::string(key) + "' is a " +
                         std::string(Dictionary::kind_name(value.kind())) + ", not a number");
      }
      out = value.as_number();
    };
    for (const ServoCommandField& field : kServoCommandFields)
      read(field.key, command.*field.member);
    if (maximum_torques != nullptr &&
        !(command.maximum_torque >= 0.0 && command.maximum_torque <= (*maximum_torques)[i])) {
      throw SpineError("action servo." + std::string(kServoNames[i]) +
                       ".maximum_torque = " + std::to_string(command.maximum_torque) +
                       " N.m is outside [0, " + std::to_string((*maximum_torques)[i]) + "]");
    }
  }
}

}  // namespace upkie_rl
