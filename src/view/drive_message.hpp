#pragma once
/// @file
/// DriveMessage: a message of the page, parsed and checked (drive_protocol.hpp).

#include <cstdint>
#include <string_view>

#include "view/drive_protocol.hpp"
#include "view/view_error.hpp"

namespace upkie_rl {

/// Raised on a page's message that is refused; the message names the problem (sent back to
/// the page as the reason).
class DriveMessageError : public ViewError {
 public:
  using ViewError::ViewError;
};

/// What a page asks.
struct DriveMessage {
  enum class Kind { kCommand, kReset, kPause, kPush };
  Kind kind = Kind::kCommand;
  std::uint64_t sequence = 0;     ///< kCommand: the page's number of the command.
  double forward_velocity = 0.0;  ///< kCommand [m/s]
  double yaw_rate = 0.0;          ///< kCommand [rad/s]
  double height = 0.557;          ///< kCommand [m]: limits.max_height without "height"
  double heading = 0.0;           ///< kPush: direction in the robot's frame [rad]
};

/// Parses a text message of the page.
/// @throws DriveMessageError naming the problem: not JSON, not an object, an unknown type,
///         a missing key or one that is not a number, a value that is not finite, a
///         velocity or height outside `limits` (a height without limits.height_command),
///         a sequence number that is not a whole number >= 0.
DriveMessage parse_drive_message(std::string_view text, const DriveLimits& limits);

}  // namespace upkie_rl
