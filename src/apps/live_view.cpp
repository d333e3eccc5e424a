#include "apps/live_view.hpp"

#include <algorithm>
#include <iostream>
#include <stdexcept>
#include <thread>

#include "apps/interrupt_handlers.hpp"
#include "apps/option_checks.hpp"
#include "model/robot_model.hpp"
#include "view/view_frame.hpp"
#include "view/view_session.hpp"

namespace upkie_rl::apps {

void add_view_address_options(CLI::App& command, std::string& host, int& port,
                              bool hidden_aliases) {
  command.add_option("--view-host", host, "Address the viewer listens on")->capture_default_str();
  command.add_option("--view-port", port, "Port of the viewer; 0 picks a free one")
      ->check(finite_range(0, 65535))
      ->capture_default_str();
  if (hidden_aliases) {
    // Former spellings of `upkie-rl view`, accepted and left out of --help.
    command.add_option("--host", host)->group("");
    command.add_option("--port", port)->check(finite_range(0, 65535))->group("");
  }
}

void add_live_view_options(CLI::App& command, LiveViewOptions& options, bool pacing) {
  command.add_flag("--view", options.enabled,
                   "Serve a live 3-D view in the browser (the URL is printed)");
  add_view_address_options(command, options.host, options.port, false);
  command
      .add_option("--view-wait", options.wait_clients,
                  "Wait for this many browsers before the first step")
      ->check(finite_range(0, 1000))
      ->capture_default_str();
  command
      .add_option("--view-max-connections", options.max_connections,
                  "Open connections the viewer accepts; more are closed at once")
      ->check(finite_range(1, 65536))
      ->capture_default_str();
  command
      .add_option("--view-idle-timeout", options.idle_timeout,
                  "Seconds a connection may stay silent before the viewer closes it")
      ->check(finite_range(0.1, 3600.0))
      ->capture_default_str();
  if (pacing) {
    command
        .add_option("--view-speed", options.speed,
                    "Simulated seconds per second while viewing; 0: as fast as possible")
        ->check(finite_range(0.0, 1000.0))
        ->capture_default_str();
  }
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
  std::cout << "viewer: waiting for " << count << " browser(s) at " << server_->url() << std::endl;
  // Ctrl-C or SIGTERM while nobody comes ends the command with an error, not a hang.
  const InterruptHandlers interrupts;
  while (!server_->wait_for_clients(count, std::chrono::seconds(3600), &interrupt_requested)) {
    if (interrupt_requested.load()) {
      throw std::runtime_error("interrupted while waiting for " + std::to_string(count) +
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
