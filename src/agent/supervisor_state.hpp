#pragma once
/// @file
/// The states of the robot runner's supervisor.

#include <string_view>

namespace upkie_rl {

/// idle (policy loaded, nothing sent) -> starting (spine started, first observation
/// checked) -> running (policy in the loop) -> stopping (stop commands, then Stop) ->
/// stopped (detached). Any state may go to stopping; stopping always ends in stopped.
/// The values are the flight recorder's `supervisor_state` column.
enum class SupervisorState { kIdle = 0, kStarting = 1, kRunning = 2, kStopping = 3, kStopped = 4 };

/// "idle", "starting", "running", "stopping" or "stopped".
constexpr std::string_view supervisor_state_name(SupervisorState state) {
  switch (state) {
    case SupervisorState::kIdle:
      return "idle";
    case SupervisorState::kStarting:
      return "starting";
    case SupervisorState::kRunning:
      return "running";
    case SupervisorState::kStopping:
      return "stopping";
    case SupervisorState::kStopped:
    default:
      return "stopped";
  }
}

}  // namespace upkie_rl
