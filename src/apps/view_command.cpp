/// @file
/// `upkie-rl view`: the 3-D viewer in the browser, for a recorded episode file (replay) or
/// the robot at rest; `--html` writes the replay as one self-contained file instead.

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "apps/commands.hpp"
#include "cli/command_error.hpp"
#include "cli/interrupt_handlers.hpp"
#include "cli/live_view.hpp"
#include "cli/option_checks.hpp"
#include "cli/velocity_view.hpp"
#include "envs/records/record_file.hpp"
#include "envs/registry/env_factory.hpp"
#include "model/robot_model.hpp"
#include "view/view_frame.hpp"
#include "view/view_server.hpp"
#include "view/view_session.hpp"
#include "view/viewer_page.hpp"

namespace upkie_rl::apps {
namespace {

struct ViewOptions {
  std::string record_path;
  std::string html_path;
  std::string host = "127.0.0.1";
  int port = 7000;
  std::string title;
};

/// The replay of a record file: one episode per episode number, each row a frame whose
/// return is the sum of the rewards of the rows before it.
ViewSession replay_session(const RecordFile& record, const std::string& title) {
  ViewSession session;
  session.mode = ViewSession::Mode::kReplay;
  session.title = title;
  session.action_names = record.action_names;
  if (record.has_velocity()) add_velocity_charts(session);
  const std::size_t frame_size = view_session_frame_size(session);
  const std::size_t num_extra = session.extra_fields.size();
  std::vector<double> frame(frame_size);
  std::vector<float> action;
  double episode_return = 0.0;
  for (std::size_t row = 0; row < record.steps.size(); ++row) {
    const RecordedStep& step = record.steps[row];
    if (session.episodes.empty() || session.episodes.back().episode != step.episode) {
      session.episodes.push_back({step.episode, {}});
      episode_return = 0.0;
    }
    // The row as the observation it recorded, so that one writer fills every frame.
    Observation observation;
    observation.time = step.time;
    observation.base_orientation.pitch = step.pitch;
    observation.wheel_odometry.position = step.ground_position;
    observation.has_sim = true;
    observation.sim_base.position = step.pose.base_position;
    observation.sim_base.orientation = step.pose.base_orientation.normalized();
    for (std::size_t servo = 0; servo < kNumServos; ++servo) {
      observation.servo[servo].position = step.pose.joint_angles[servo];
    }
    action.assign(step.action.begin(), step.action.end());
    const std::span<double> frame_row(frame);
    write_view_frame(observation, {step.episode, step.step, episode_return}, action,
                     frame_row.first(frame_size - num_extra));
    if (record.has_velocity()) {
      write_velocity_fields(*step.command, *step.measured, frame_row.last(num_extra));
    }
    std::vector<double>& frames = session.episodes.back().frames;
    frames.insert(frames.end(), frame.begin(), frame.end());
    episode_return += step.reward;
    if (row + 1 < record.steps.size() && record.steps[row + 1].episode == step.episode &&
        session.episodes.back().frames.size() == frame_size) {
      session.timestep = record.steps[row + 1].time - step.time;
    }
  }
  if (!(session.timestep > 0.0)) session.timestep = 0.005;
  return session;
}

/// The robot at rest: the first observation of the simulated servos environment.
ViewSession rest_session() {
  std::unique_ptr<Env> env = make_env("Upkie-Bullet-Servos", {});
  std::vector<float> observation(env->observation_space().size());
  env->reset(0, observation);
  ViewSession session;
  session.mode = ViewSession::Mode::kReplay;
  session.title = "Upkie at rest (Upkie-Bullet-Servos after a reset)";
  session.timestep = env->timestep();
  std::vector<double> frame(view_frame_size(0));
  write_view_frame(*env->full_observation(), {}, {}, frame);
  session.episodes.push_back({0, frame});
  return session;
}

void run_view(const ViewOptions& options) {
  ViewSession session;
  if (options.record_path.empty()) {
    session = rest_session();
  } else {
    const RecordFile record = read_record_file(options.record_path);
    session = replay_session(record, options.title.empty() ? options.record_path : options.title);
    std::cout << options.record_path << ": " << session.episodes.size() << " episode(s), "
              << record.steps.size() << " steps, actions:";
    for (const std::string& name : record.action_names) std::cout << ' ' << name;
    std::cout << std::endl;
  }
  const std::string session_json =
      view_session_json(session, RobotModel::default_urdf_path().string());
  if (!options.html_path.empty()) {
    std::ofstream out(options.html_path, std::ios::out | std::ios::trunc | std::ios::binary);
    out << self_contained_viewer_page(session_json);
    out.close();
    if (!out) throw CommandError("cannot write " + options.html_path);
    std::cout << "wrote " << options.html_path << " ("
              << std::filesystem::file_size(options.html_path)
              << " bytes): open it in a browser, no server needed" << std::endl;
    return;
  }
  ViewServerConfig config;
  config.host = options.host;
  config.port = options.port;
  InterruptHandlers handlers;
  const ViewServer server(config, session_json, nullptr);
  std::cout << "viewer: " << server.url() << " (Ctrl-C stops it)" << std::endl;
  while (!interrupt_requested.load()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  std::cout << "viewer: stopped after " << server.statistics().http_requests << " requests"
            << std::endl;
}

}  // namespace

void add_view_command(CLI::App& app) {
  auto options = std::make_shared<ViewOptions>();
  CLI::App* command = app.add_subcommand(
      "view",
      "3-D viewer in the browser: replay a file of `rollout --record` (or show the robot at "
      "rest); --html writes the replay as one self-contained file");
  command->add_option("record", options->record_path, "Record file (CSV) to replay")
      ->check(CLI::ExistingFile);
  command
      ->add_option("--html", options->html_path,
                   "Write a self-contained HTML replay to this file instead of serving")
      ->check(kNonEmptyPath);
  add_view_address_options(*command, options->host, options->port, true);
  command->add_option("--title", options->title, "Title shown in the page (default: the file)");
  command->callback([options] { run_view(*options); });
}

}  // namespace upkie_rl::apps
