#pragma once
/// @file
/// The session document the viewer page reads first: what it shows (live or replay), the
/// frame columns, the robot's URDF, and for a replay every frame.

#include <optional>
#include <string>
#include <vector>

#include "view/drive_protocol.hpp"

namespace upkie_rl {

/// What a viewer page shows.
struct ViewSession {
  enum class Mode { kLive, kReplay };
  struct Episode {
    int episode = 0;
    std::vector<double> frames;  ///< Row-major, view_frame_size(action_names.size()) per frame.
  };

  /// A chart of extra fields, plotted and shown in the HUD beside the standard ones.
  struct Chart {
    std::string title;  ///< With its unit, e.g. "Forward velocity [m/s]".
    struct Series {
      std::string label;  ///< e.g. "command".
      std::string field;  ///< One of extra_fields.
    };
    std::vector<Series> series;
  };

  Mode mode = Mode::kLive;
  std::string title;                      ///< Shown above the scene.
  double timestep = 0.005;                ///< Time between frames [s].
  std::vector<std::string> action_names;  ///< Of the environment's action space.
  std::vector<Episode> episodes;          ///< Replay only.
  /// Columns after the actions in every frame (e.g. the command and the measured velocity).
  std::vector<std::string> extra_fields;
  std::vector<Chart> charts;  ///< Of extra_fields.
  /// Set when pages may drive (`upkie-rl drive`): the protocol's keys and the limits.
  std::optional<DriveLimits> drive;
};

/// Number of columns of the frames of `session`: view_frame_size of its actions, plus its
/// extra fields.
std::size_t view_session_frame_size(const ViewSession& session);

/// Path of the WebSocket of live frames on the viewer's server.
inline constexpr const char* kViewFramesPath = "/frames";

/// The session as the page reads it (JSON): version, mode, title, timestep, frame_fields,
/// action_names, charts, urdf (the text of `urdf_path`), websocket (live) or episodes
/// (replay), and drive (drive_protocol_json) when pages may drive.
/// @throws ViewError when a chart names a field that is not an extra field.
/// @throws ViewError when the URDF cannot be read or an episode's frames are not whole
///         frames.
std::string view_session_json(const ViewSession& session, const std::string& urdf_path);

}  // namespace upkie_rl
