#pragma once
/// @file
/// What an agent asks of one servo, and of all six.

#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>
#include <string_view>

#include "model/error.hpp"
#include "model/joint_order.hpp"

namespace upkie_rl {

/// One servo's command (moteus position mode). The servo law evaluated at every physics
/// step is tau = clamp(feedforward_torque + kp*kp_scale*(position - q)
///                     + kd*kd_scale*(velocity - qdot), +-min(maximum_torque, effort)).
struct ServoCommand {
  /// Target angle [rad]; NaN drops the position term ("no position loop").
  double position = std::numeric_limits<double>::quiet_NaN();
  /// Target velocity [rad/s]; never NaN.
  double velocity = 0.0;
  /// Feedforward torque [N.m].
  double feedforward_torque = 0.0;
  /// Multiplies the position gain kp, in [0, 5].
  double kp_scale = 1.0;
  /// Multiplies the velocity gain kd, in [0, 5].
  double kd_scale = 1.0;
  /// Clamp of the total torque [N.m]; the joint effort limit applies on top of it.
  double maximum_torque = std::numeric_limits<double>::infinity();
};

/// Commands for the six servos in the standard joint order (see joint_order.hpp).
using ServoAction = std::array<ServoCommand, kNumServos>;

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

/// Raised when a command is not acceptable (a NaN or infinite velocity, torque or gain).
class InvalidCommandError : public Error {
 public:
  using Error::Error;
};

/// Where a servo action goes: a simulation takes the +inf maximum torque of the table
/// ("no clamp beyond the effort limit"); the robot gets finite values only.
enum class ServoActionTarget { kSimulation, kRobot };

/// Checks every field of kServoCommandFields: finite, except where the table allows NaN (a
/// NaN position is the documented "no position loop") or, for a simulation, +inf (a
/// maximum_torque of +inf is "no clamp beyond the effort limit").
/// @throws InvalidCommandError naming the joint and the field.
void validate_servo_action(const ServoAction& action,
                           ServoActionTarget target = ServoActionTarget::kSimulation);

}  // namespace upkie_rl
