#pragma once
/// @file
/// LiveView: the `--view` option of rollout, train and spine. It serves the viewer page and
/// streams one robot's steps to the browsers connected to it, paced at the simulation's
/// rate (or a multiple of it) when asked.

#include <CLI/CLI.hpp>
#include <chrono>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "sim/observation.hpp"
#include "view/drive_control.hpp"
#include "view/frame_broadcaster.hpp"
#include "view/view_server.hpp"
#include "view/view_session.hpp"

namespace upkie_rl::apps {

/// Options of `--view`.
struct LiveViewOptions {
  bool enabled = false;
  std::string host = "127.0.0.1";
  int port = 7000;
  /// Simulated seconds per wall-clock second; 0 runs as fast as the run goes (frames the
  /// browsers cannot take are dropped).
  double speed = 1.0;
  /// Wait for this many browsers before the first step.
  int wait_clients = 0;
  /// Open connections the viewer accepts (ViewServerConfig::max_connections).
  int max_connections = 128;
  /// Seconds an HTTP connection may stay silent (ViewServerConfig::idle_timeout).
  double idle_timeout = 10.0;
};

/// The range of --view-speed and what it means for a command.
struct ViewSpeedRange {
  double min;
  double max;
  const char* help;
};
/// A run watched: any pace, as fast as it goes included.
inline constexpr ViewSpeedRange kWatchedSpeed{
    0.0, 1000.0, "Simulated seconds per wall-clock second while viewing; 0: as fast as possible"};
/// A run a person drives: real time or near it.
inline constexpr ViewSpeedRange kDrivenSpeed{0.05, 10.0, "Simulated seconds per wall-clock second"};

/// Adds --view-host and --view-port, the viewer's address in every command; with
/// `former_spellings`, also --host and --port (add_former_spelling), as `view` and `drive`
/// were first spelt.
void add_view_address_options(CLI::App& command, std::string& host, int& port,
                              bool former_spellings);

/// Adds the viewer's address, --view-wait, --view-max-connections, --view-idle-timeout and
/// (with a `speed` range) --view-speed; with `former_spellings`, also --host, --port, --wait
/// and --speed, as `drive` was first spelt.
void add_view_server_options(CLI::App& command, LiveViewOptions& options,
                             const ViewSpeedRange* speed, bool former_spellings);

/// Adds --view, then add_view_server_options (with kWatchedSpeed when `pacing`).
void add_live_view_options(CLI::App& command, LiveViewOptions& options, bool pacing);

/// A live viewer of one robot.
class LiveView {
 public:
  /// Serves the page and prints its URL.
  /// @param title Shown in the page.
  /// @param timestep Simulated time between steps [s].
  /// @param action_names Of the action space (the first kMaxViewActions are plotted).
  /// @throws ViewError when the server cannot listen.
  LiveView(const LiveViewOptions& options, const std::string& title, double timestep,
           const std::vector<std::string>& action_names);
  /// The same for a session prepared by the caller (its mode is set to live): extra fields
  /// and charts, and with `drive`, pages that drive (session.drive is then set).
  LiveView(const LiveViewOptions& options, ViewSession session,
           std::shared_ptr<DriveControl> drive = nullptr);
  ~LiveView();

  /// Waits for options.wait_clients browsers (returns at once without), printing why.
  void wait_for_browsers();

  /// Starts pacing a new episode.
  void start_episode(int episode);

  /// Paces from the next frame on, as at an episode's start (after a pause).
  void restart_pacing() { first_frame_ = true; }

  /// Publishes the frame of `observation` after `step` steps of the current episode, then
  /// waits until the wall clock catches up with the simulation (when paced). `action` is the
  /// one that led here (the neutral action at step 0); `extra` the session's extra fields.
  /// Allocates nothing.
  void publish(const Observation& observation, int step, double episode_return,
               std::span<const float> action, std::span<const double> extra = {});

  /// Tells the browsers that the run is over and why.
  void end(const std::string& reason);

  const ViewServer& server() const { return *server_; }

 private:
  LiveViewOptions options_;
  std::shared_ptr<FrameBroadcaster> frames_;
  std::unique_ptr<ViewServer> server_;
  std::vector<double> frame_;
  std::size_t num_extra_fields_ = 0;
  int episode_ = 0;
  std::chrono::steady_clock::time_point episode_start_;
  double episode_start_time_ = 0.0;  ///< Simulated time of the episode's first frame.
  bool first_frame_ = true;
};

}  // namespace upkie_rl::apps
