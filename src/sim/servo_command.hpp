#pragma once
/// @file
/// What an agent asks of one servo, and of all six.

#include <array>
#include <limits>
#include <stdexcept>

#include "base/error.hpp"
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

/// Raised when a command is not acceptable (a NaN or infinite velocity, torque or gain).
class InvalidCommandError : public Error {
 public:
  using Error::Error;
};

/// Where a servo action goes: a simulation takes the +inf maximum torque of the table
/// ("no clamp beyond the effort limit"); the robot gets finite values only.
enum class ServoActionTarget { kSimulation, kRobot };

/// Checks every field of kServoCommandFields (sim/servo_command_fields.hpp): finite, except where
/// the table allows NaN (a NaN position is the documented "no position loop") or, for a simulation,
/// +inf (a maximum_torque of +inf is "no clamp beyond the effort limit").
/// @throws InvalidCommandError naming the joint and the field.
void validate_servo_action(const ServoAction& action,
                           ServoActionTarget target = ServoActionTarget::kSimulation);

}  // namespace upkie_rl
