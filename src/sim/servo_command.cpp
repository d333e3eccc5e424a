#include "sim/servo_command.hpp"

#include <cmath>
#include <string>

namespace upkie_rl {
namespace {

[[noreturn]] void refuse(std::size_t servo, const char* field, double value) {
  throw InvalidCommandError("servo command for '" + std::string(kServoNames[servo]) +
                            "': " + field + " must be finite, got " + std::to_string(value));
}

}  // namespace

void validate_servo_action(const ServoAction& action) {
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    const ServoCommand& command = action[servo];
    if (std::isinf(command.position)) refuse(servo, "position", command.position);
    if (!std::isfinite(command.velocity)) refuse(servo, "velocity", command.velocity);
    if (!std::isfinite(command.feedforward_torque)) {
      refuse(servo, "feedforward_torque", command.feedforward_torque);
    }
    if (!std::isfinite(command.kp_scale)) refuse(servo, "kp_scale", command.kp_scale);
    if (!std::isfinite(command.kd_scale)) refuse(servo, "kd_scale", command.kd_scale);
    if (std::isnan(command.maximum_torque) || command.maximum_torque == -INFINITY) {
      refuse(servo, "maximum_torque", command.maximum_torque);
    }
  }
}

}  // namespace upkie_rl
