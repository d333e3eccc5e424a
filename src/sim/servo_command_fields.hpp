#pragma once
/// @file
/// The fields of a ServoCommand declared once, for every wire format and check that names
/// them.

#include <algorithm>
#include <array>
#include <string_view>

#include "sim/servo_command.hpp"

namespace upkie_rl {

/// The key of the per-joint servo maps in the spine's action and observation dictionaries.
inline constexpr std::string_view kServoMapKey = "servo";

/// One field of a ServoCommand as every wire format spells it (the spine's action
/// dictionary `servo.<joint>.<key>`, the servos environment's flat action `<joint>.<key>`,
/// error messages).
struct ServoCommandField {
  std::string_view key;
  double ServoCommand::*member;
  /// NaN is a legal value ("no position loop"); an infinity never is.
  bool nan_allowed = false;
  /// +infinity is a legal value in a simulation ("no clamp beyond the effort limit").
  bool positive_infinity_allowed = false;
};

/// The fields of a ServoCommand, declared once, in the servos environment's flat order
/// (position, velocity, feedforward_torque, kp_scale, kd_scale, maximum_torque): the
/// spine's action writer and reader, the command checks and the environment all loop over
/// this table, so a field added here reaches every one of them.
inline constexpr std::array<ServoCommandField, 6> kServoCommandFields = {{
    {"position", &ServoCommand::position, true, false},
    {"velocity", &ServoCommand::velocity},
    {"feedforward_torque", &ServoCommand::feedforward_torque},
    {"kp_scale", &ServoCommand::kp_scale},
    {"kd_scale", &ServoCommand::kd_scale},
    {"maximum_torque", &ServoCommand::maximum_torque, false, true},
}};

/// kServoCommandFields in byte-wise key order: the order of the spine's msgpack maps.
inline constexpr std::array<ServoCommandField, kServoCommandFields.size()>
    kServoCommandFieldsByKey = [] {
      auto fields = kServoCommandFields;
      std::sort(
          fields.begin(), fields.end(),
          [](const ServoCommandField& a, const ServoCommandField& b) { return a.key < b.key; });
      return fields;
    }();

}  // namespace upkie_rl
