#pragma once
/// @file
/// The driving protocol between the viewer page and `upkie-rl drive`: every key of the
/// JSON text messages either way, declared once here. The session document carries them
/// (drive_protocol_json), and the page builds and reads its messages with those names.
///
/// Page to server:
///   {"type": "command", "seq": N, "forward_velocity": v, "yaw_rate": w, "height": h}
///     (height [m] only for a task with a height command; without it, standing)
///   {"type": "reset"}, {"type": "pause"} (toggles), {"type": "push", "heading": a}
///     (a push toward the direction `a` [rad] in the robot's frame: 0 forward, π/2 left)
/// Server to page:
///   {"type": "drive_status", "role": "driver" | "watcher" | "free", "paused": bool,
///    "reason": text}
///   {"type": "refused", "reason": text}
///   {"type": "applied", "seq": N} (the command N reached the simulation)

#include <nlohmann/json_fwd.hpp>

namespace upkie_rl::drive_keys {

inline constexpr const char* kType = "type";
inline constexpr const char* kReason = "reason";

// Page to server.
inline constexpr const char* kCommand = "command";
inline constexpr const char* kSequence = "seq";
inline constexpr const char* kForwardVelocity = "forward_velocity";
inline constexpr const char* kYawRate = "yaw_rate";
inline constexpr const char* kHeight = "height";
inline constexpr const char* kReset = "reset";
inline constexpr const char* kPause = "pause";
inline constexpr const char* kPush = "push";
inline constexpr const char* kHeading = "heading";

// Server to page.
inline constexpr const char* kStatus = "drive_status";
inline constexpr const char* kRole = "role";
inline constexpr const char* kPaused = "paused";
inline constexpr const char* kRefused = "refused";
inline constexpr const char* kApplied = "applied";

// Values of kRole.
inline constexpr const char* kDriver = "driver";
inline constexpr const char* kWatcher = "watcher";
inline constexpr const char* kFree = "free";

}  // namespace upkie_rl::drive_keys

namespace upkie_rl {

/// Limits of the commands a page may send (the environment's command ranges).
struct DriveLimits {
  double max_forward_velocity = 1.0;  ///< |forward_velocity| at most this [m/s].
  double max_yaw_rate = 1.5;          ///< |yaw_rate| at most this [rad/s].
  bool height_command = false;        ///< Whether commands may carry a base height.
  double min_height = 0.53;           ///< Lowest height with height_command [m].
  double max_height = 0.557;          ///< Highest height (standing) with height_command [m].
};

/// The "drive" section of the session document: {"keys": {name: wire key}, "limits":
/// {"max_forward_velocity", "max_yaw_rate"[, "min_height", "max_height"]}} (the heights
/// with a height command only). The page takes every key from it.
nlohmann::json drive_protocol_json(const DriveLimits& limits);

}  // namespace upkie_rl
