#include "view/drive_message.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

namespace upkie_rl {

namespace {

/// The number under `key` of `message`.
double number_at(const nlohmann::json& message, const char* key) {
  const auto found = message.find(key);
  if (found == message.end()) {
    throw DriveMessageError(std::string("no \"") + key + "\" in the message");
  }
  if (!found->is_number()) throw DriveMessageError(std::string("\"") + key + "\" is not a number");
  const double value = found->get<double>();
  if (!std::isfinite(value)) throw DriveMessageError(std::string("\"") + key + "\" is not finite");
  return value;
}

/// The number under `key`, within ±`limit`.
double bounded_at(const nlohmann::json& message, const char* key, double limit) {
  const double value = number_at(message, key);
  if (std::abs(value) > limit) {
    throw DriveMessageError(std::string("\"") + key + "\" " + std::to_string(value) +
                            " is outside [-" + std::to_string(limit) + ", " +
                            std::to_string(limit) + "]");
  }
  return value;
}

/// The optional height of a command message [m]: within the limits' height range, or their
/// top (standing) when absent.
double height_at(const nlohmann::json& message, const DriveLimits& limits) {
  if (!message.contains(drive_keys::kHeight)) return limits.max_height;
  if (!limits.height_command) {
    throw DriveMessageError(std::string("\"") + drive_keys::kHeight +
                            "\" given, but the task has no height command");
  }
  const double value = number_at(message, drive_keys::kHeight);
  if (value < limits.min_height || value > limits.max_height) {
    throw DriveMessageError(
        std::string("\"") + drive_keys::kHeight + "\" " + std::to_string(value) + " is outside [" +
        std::to_string(limits.min_height) + ", " + std::to_string(limits.max_height) + "]");
  }
  return value;
}

}  // namespace

DriveMessage parse_drive_message(std::string_view text, const DriveLimits& limits) {
  namespace k = drive_keys;
  const nlohmann::json message = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (message.is_discarded()) throw DriveMessageError("the message is not JSON");
  if (!message.is_object()) throw DriveMessageError("the message is not a JSON object");
  const auto type = message.find(k::kType);
  if (type == message.end() || !type->is_string()) {
    throw DriveMessageError(std::string("the message has no \"") + k::kType + "\" string");
  }
  const std::string& name = type->get_ref<const std::string&>();
  DriveMessage parsed;
  if (name == k::kCommand) {
    parsed.kind = DriveMessage::Kind::kCommand;
    const double sequence = number_at(message, k::kSequence);
    if (sequence < 0.0 || sequence != std::floor(sequence) || sequence > 9.0e15) {
      throw DriveMessageError(std::string("\"") + k::kSequence + "\" is not a whole number >= 0");
    }
    parsed.sequence = static_cast<std::uint64_t>(sequence);
    parsed.forward_velocity = bounded_at(message, k::kForwardVelocity, limits.max_forward_velocity);
    parsed.yaw_rate = bounded_at(message, k::kYawRate, limits.max_yaw_rate);
    parsed.height = height_at(message, limits);
  } else if (name == k::kReset) {
    parsed.kind = DriveMessage::Kind::kReset;
  } else if (name == k::kPause) {
    parsed.kind = DriveMessage::Kind::kPause;
  } else if (name == k::kPush) {
    parsed.kind = DriveMessage::Kind::kPush;
    parsed.heading = bounded_at(message, k::kHeading, 2.0 * M_PI);
  } else {
    throw DriveMessageError("unknown message type \"" + name + "\"");
  }
  return parsed;
}

}  // namespace upkie_rl
