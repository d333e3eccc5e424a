#include "cli/live_view.hpp"

#include <algorithm>
#include <iostream>
#include <stdexcept>
#include <thread>

#include "cli/command_error.hpp"
#include "cli/common_flags.hpp"
#include "cli/interrupt_handlers.hpp"
#include "cli/option_checks.hpp"
#include "model/robot_model.hpp"
#include "view/view_frame.hpp"
#include "view/view_session.hpp"

namespace upkie_rl::apps {

namespace {

/// --view-<name>, and with `former_spelling`, its former spelling --<name>.
template <typename Value>
void add_view_flag(CLI::App& command, const std::string& name, Value& target,
                   const std::string& help, const CLI::Validator& check, bool former_spelling) {
  command.add_option("--view-" + name, target, help)->check(check)->capture_default_str();
  if (former_spelling) {
    add_former_spelling(command, "--" + name, "--view-" + name, target, check);
  }
}

}  // namespace

void add_view_address_options(CLI::App& command, std::string& host, int& port,
                              bool former_spellings) {
  add_view_flag(command, "host", host, "Address the viewer listens on", CLI::Validator(),
                former_spellings);
  add_view_flag(command, "port", port, "Port of the viewer; 0 picks a free one",
                finite_range(0, 65535), former_spellings);
}

void add_view_server_options(CLI::App& command, LiveViewOptions& options,
                             const ViewSpeedRange* speed, bool former_spellings) {
  add_view_address_options(command, options.host, options.port, former_spellings);
  add_view_flag(command, "wait", options.wait_clients,
                "Wait for this many browsers before the first step", finite_range(0, 1000),
                former_spellings);
  add_view_flag(command, "max-connections", options.max_connections,
                "Open connections the viewer accepts; more are closed at once",
                finite_range(1, 65536), false);
  add_view_flag(command, "idle-timeout", options.idle_timeout,
                "Seconds a connection may stay silent before the viewer closes it",
                finite_range(0.1, 3600.0), false);
  if (speed != nullptr) {
    add_view_flag(command, "speed", options.speed, speed->help,
                  finite_range(speed->min, speed->max), former_spellings);
  }
}

void add_live_view_options(CLI::App& command, LiveViewOptions& options, bool pacing) {
  command.add_flag("--view", options.enabled,
                   "Serve a live 3-D view in the browser (the URL is printed)");
  add_view_server_options(command, options, pacing ? &kWatchedSpeed : nullptr, false);
}

namespace {

ViewSession live_session(const std::string& title, double timestep,
                         const std::vector<std::string>& action_names) {
  ViewSession session;
  session.title = title;
  session.timestep = timestep;
  session.action_names = action_names;
  return session;
}

}  // namespace

LiveView::LiveView(const LiveViewOptions& options, const std::string& title, double timestep,
                   const std::vector<std::string>& action_names)
    : LiveView(options, live_session(title, timestep, action_names)) {}

LiveView::LiveView(const LiveViewOptions& options, ViewSession session,
                   std::shared_ptr<DriveControl> drive)
    : options_(options),
      frames_(std::make_shared<FrameBroadcaster>(view_session_frame_size(session))),
      frame_(view_session_frame_size(session)),
      num_extra_fields_(session.extra_fields.size()) {
  session.mode = ViewSession::Mode::kLive;
  if (drive) session.drive = drive->limits();
  ViewServerConfig config;
  config.host = options.host;
  config.port = options.port;
  config.max_connections = static_cast<std::size_t>(options.max_connections);
  config.idle_timeout = options.idle_timeout;
  server_ = std::make_unique<ViewServer>(
      config, view_session_json(session, RobotModel::default_urdf_path().string()), frames_,
      std::move(drive));
  std::cout << "viewer: " << server_->url() << std::endl;
}

LiveView::~LiveView() = default;

void LiveView::wait_for_browsers() {
  if (options_.wait_clients <= 0) return;
  const auto count = static_cast<std::size_t>(options_.wait_clients);
  // Ctrl-C or SIGTERM while nobody comes ends the command with an error, not a hang. The
  // handlers come before the line that says so: a script (or a test) that signals once it
  // reads the line must find them installed.
  const InterruptHandlers interrupts;
  std::cout << "viewer: waiting for " << count << " browser(s) at " << server_->url() << std::endl;
  while (!server_->wait_for_clients(count, std::chrono::seconds(3600), &interrupt_requested)) {
    if (interrupt_requested.load()) {
      throw CommandError("interrupted while waiting for " + std::to_string(count) +
                         " browser(s) (--view-wait)");
    }
  }
}

void LiveView::start_episode(int episode) {
  episode_ = episode;
  first_frame_ = true;
}

void LiveView::publish(const Observation& observation, int step, double episode_return,
                       std::span<const float> action, std::span<const double> extra) {
  const std::span<double> frame(frame_);
  write_view_frame(observation, {episode_, step, episode_return}, action,
                   frame.first(frame.size() - num_extra_fields_));
  if (extra.size() != num_extra_fields_) {
    throw std::invalid_argument("LiveView: " + std::to_string(extra.size()) + " extra values for " +
                                std::to_string(num_extra_fields_) + " extra fields");
  }
  std::copy(extra.begin(), extra.end(), frame.end() - static_cast<std::ptrdiff_t>(extra.size()));
  frames_->publish(frame_);
  if (!(options_.speed > 0.0)) return;
  const auto now = std::chrono::steady_clock::now();
  if (first_frame_) {
    first_frame_ = false;
    episode_start_ = now;
    episode_start_time_ = observation.time;
    return;
  }
  const auto due =
      episode_start_ +
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>((observation.time - episode_start_time_) / options_.speed));
  if (due > now) std::this_thread::sleep_until(due);
}

void LiveView::end(const std::string& reason) { server_->end(reason); }

}  // namespace upkie_rl::apps
