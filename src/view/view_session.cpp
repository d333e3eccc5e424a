#include "view/view_session.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/input_file.hpp"
#include "model/robot_description_limit.hpp"
#include "view/view_error.hpp"
#include "view/view_frame.hpp"

namespace upkie_rl {

namespace {

std::string read_text(const std::string& path) {
  std::string text =
      read_input_file<ViewError>(path, "robot description", kMaxRobotDescriptionBytes);
  if (text.empty()) throw ViewError("robot description " + path + ": empty file");
  return text;
}

}  // namespace

std::size_t view_session_frame_size(const ViewSession& session) {
  return view_frame_size(session.action_names.size()) + session.extra_fields.size();
}

std::string view_session_json(const ViewSession& session, const std::string& urdf_path) {
  std::vector<std::string> fields = view_frame_fields(session.action_names);
  fields.insert(fields.end(), session.extra_fields.begin(), session.extra_fields.end());
  nlohmann::json charts = nlohmann::json::array();
  for (const ViewSession::Chart& chart : session.charts) {
    nlohmann::json series = nlohmann::json::array();
    for (const ViewSession::Chart::Series& curve : chart.series) {
      if (std::find(session.extra_fields.begin(), session.extra_fields.end(), curve.field) ==
          session.extra_fields.end()) {
        throw ViewError("chart \"" + chart.title + "\" plots \"" + curve.field +
                        "\", which is not an extra field of the frames");
      }
      series.push_back({{"label", curve.label}, {"field", curve.field}});
    }
    charts.push_back({{"title", chart.title}, {"series", std::move(series)}});
  }
  nlohmann::json document = {
      {"version", 1},
      {"mode", session.mode == ViewSession::Mode::kLive ? "live" : "replay"},
      {"title", session.title},
      {"timestep", session.timestep},
      {"frame_fields", fields},
      {"action_names", session.action_names},
      {"charts", std::move(charts)},
      {"urdf", read_text(urdf_path)},
  };
  if (session.mode == ViewSession::Mode::kLive) {
    document["websocket"] = kViewFramesPath;
    if (session.drive) document["drive"] = drive_protocol_json(*session.drive);
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
