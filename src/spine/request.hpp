#pragma once
/// @file
/// The request word of the spine's shared memory: what the agent asks the spine to do.

#include <cstdint>
#include <string_view>

namespace upkie_rl {

/// Request codes of the current Upkie spine protocol (spine.md section 1). The older
/// numbering (None 0, Observation 1, Action 2, Start 3, Stop 4, Error 5) is not supported.
enum class Request : std::uint32_t {
  kNone = 0,    ///< No pending request; the spine sets it when it is done with one.
  kAction = 1,  ///< An action is in the payload: apply it and write the observation.
  kStart = 2,   ///< A configuration is in the payload: reset and write the observation.
  kStop = 3,    ///< Stop the actuators.
  kError = 4,   ///< Set by the spine when the last request was invalid in its state.
};

/// Name of a request code, "unknown" for values outside the protocol.
constexpr std::string_view request_name(std::uint32_t code) {
  switch (code) {
    case 0:
      return "None";
    case 1:
      return "Action";
    case 2:
      return "Start";
    case 3:
      return "Stop";
    case 4:
      return "Error";
    default:
      return "unknown";
  }
}

}  // namespace upkie_rl
