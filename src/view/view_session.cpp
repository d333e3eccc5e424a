#include "view/view_session.hpp"

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "view/view_error.hpp"
#include "view/view_frame.hpp"

namespace upkie_rl {

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in || text.str().empty()) throw ViewError("cannot read the robot description " + path);
  return text.str();
}

}  // namespace

std::string view_session_json(const ViewSession& session, const std::string& urdf_path) {
  const std::vector<std::string> fields = view_frame_fields(session.action_names);
  nlohmann::json document = {
      {"version", 1},
      {"mode", session.mode == ViewSession::Mode::kLive ? "live" : "replay"},
      {"title", session.title},
      {"timestep", session.timestep},
      {"frame_fields", fields},
      {"action_names", session.action_names},
      {"urdf", read_text(urdf_path)},
  };
  if (session.mode == ViewSession::Mode::kLive) {
    document["websocket"] = kViewFramesPath;
  } else {
    nlohmann::json episodes = nlohmann::json::array();
    for (const ViewSession::Episode& episode : session.episodes) {
      if (episode.frames.size() % fields.size() != 0) {
        throw ViewError("episode " + std::to_string(episode.episode) + " has " +
                        std::to_string(episode.frames.size()) + " values, not whole frames of " +
                        std::to_string(fields.size()));
      }
      episodes.push_back({{"episode", episode.episode}, {"frames", episode.frames}});
    }
    document["episodes"] = std::move(episodes);
  }
  return document.dump();
}

}  // namespace upkie_rl
