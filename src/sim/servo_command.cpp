#include "sim/servo_command.hpp"
#include "sim/servo_command_fields.hpp"

#include <cmath>
#include <string>
#include <string_view>

namespace upkie_rl {
namespace {

[[noreturn]] void refuse(std::size_t servo, std::string_view field, double value) {
  throw InvalidCommandError("servo command for '" + std::string(kServoNames[servo]) + "': " +
                            std::string(field) + " must be finite, got " + std::to_string(value));
}

}  // namespace

void validate_servo_action(const ServoAction& action, ServoActionTarget target) {
  const bool simulation = target == ServoActionTarget::kSimulation;
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    for (const ServoCommandField& field : kServoCommandFields) {
      const double value = action[servo].*field.member;
      const bool allowed = std::isfinite(value) || (std::isnan(value) && field.nan_allowed) ||
                           (simulation && value == INFINITY && field.positive_infinity_allowed);
      if (!allowed) refuse(servo, field.key, value);
    }
  }
}

}  // namespace upkie_rl
