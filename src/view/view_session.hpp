#pragma once
/// @file
/// The session document the viewer page reads first: what it shows (live or replay), the
/// frame columns, the robot's URDF, and for a replay every frame.

#include <string>
#include <vector>

namespace upkie_rl {

/// What a viewer page shows.
struct ViewSession {
  enum class Mode { kLive, kReplay };
  struct Episode {
    int episode = 0;
    std::vector<double> frames;  ///< Row-major, view_frame_size(action_names.size()) per frame.
  };

  Mode mode = Mode::kLive;
  std::string title;                      ///< Shown above the scene.
  double timestep = 0.005;                ///< Time between frames [s].
  std::vector<std::string> action_names;  ///< Of the environment's action space.
  std::vector<Episode> episodes;          ///< Replay only.
};

/// Path of the WebSocket of live frames on the viewer's server.
inline constexpr const char* kViewFramesPath = "/frames";

/// The session as the page reads it (JSON): version, mode, title, timestep, frame_fields,
/// action_names, urdf (the text of `urdf_path`), websocket (live) or episodes (replay).
/// @throws ViewError when the URDF cannot be read or an episode's frames are not whole
///         frames.
std::string view_session_json(const ViewSession& session, const std::string& urdf_path);

}  // namespace upkie_rl
