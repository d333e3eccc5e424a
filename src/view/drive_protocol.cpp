#include "view/drive_protocol.hpp"

#include <nlohmann/json.hpp>

namespace upkie_rl {

nlohmann::json drive_protocol_json(const DriveLimits& limits) {
  namespace k = drive_keys;
  // The page names each key by its constant's name in snake case without the k (the JSON
  // name), and sends or reads the value (the wire key).
  const nlohmann::json keys = {
      {"type", k::kType},
      {"reason", k::kReason},
      {"command", k::kCommand},
      {"seq", k::kSequence},
      {"forward_velocity", k::kForwardVelocity},
      {"yaw_rate", k::kYawRate},
      {"height", k::kHeight},
      {"reset", k::kReset},
      {"pause", k::kPause},
      {"push", k::kPush},
      {"heading", k::kHeading},
      {"status", k::kStatus},
      {"role", k::kRole},
      {"paused", k::kPaused},
      {"refused", k::kRefused},
      {"applied", k::kApplied},
      {"driver", k::kDriver},
      {"watcher", k::kWatcher},
      {"free", k::kFree},
  };
  nlohmann::json bounds = {{"max_forward_velocity", limits.max_forward_velocity},
                           {"max_yaw_rate", limits.max_yaw_rate}};
  if (limits.height_command) {
    bounds["min_height"] = limits.min_height;
    bounds["max_height"] = limits.max_height;
  }
  return {{"keys", keys}, {"limits", bounds}};
}

}  // namespace upkie_rl
