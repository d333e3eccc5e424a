/// @file
/// `upkie-rl drive`: drive a simulated robot from the browser. A velocity task runs in real
/// time with a trained policy or the classical baseline, the viewer page is served, and the
/// page that drives sends commands from the keyboard or a gamepad.

#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/commands.hpp"
#include "cli/common_flags.hpp"
#include "cli/controller_choice.hpp"
#include "cli/drive_loop.hpp"
#include "cli/interrupt_handlers.hpp"
#include "cli/live_view.hpp"
#include "cli/option_checks.hpp"
#include "cli/velocity_view.hpp"
#include "envs/registry/env_factory.hpp"
#include "envs/registry/registry.hpp"

namespace upkie_rl::apps {

namespace {

struct DriveOptions {
  std::string env_id;
  std::string controller = "lqr";
  std::string model;
  std::vector<std::string> env_options;
  std::string record_path;
  LiveViewOptions view;
  DriveLoopSettings loop;
  DriveRateSettings rate;
};

/// The environment options of a drive: no time limit unless asked (a person drives as long
/// as they like; a fall starts a new episode).
EnvOptions drive_env_options(const DriveOptions& options) {
  EnvOptions given = parse_env_options(options.env_options);
  bool has_limit = false;
  for (const auto& [key, value] : given) has_limit = has_limit || key == kMaxEpisodeStepsOption;
  if (!has_limit) given.emplace_back(kMaxEpisodeStepsOption, "0");
  return run_env_options(options.env_id, options.model, given);
}

void print_summary(const DriveSummary& summary, const DriveStatistics& statistics) {
  std::cout << "drive: " << summary.steps << " steps (" << summary.simulated_time
            << " s simulated), " << summary.episodes << " episode(s), " << summary.falls
            << " fall(s), " << summary.pushes << " push(es)" << std::endl;
  std::cout << "commands: " << statistics.commands << " accepted, " << statistics.refused
            << " refused, " << statistics.rate_limited << " over the rate limit" << std::endl;
  if (statistics.applied > 0) {
    std::cout << "command latency (received to applied): mean "
              << 1000.0 * statistics.latency_sum / static_cast<double>(statistics.applied)
              << " ms, max " << 1000.0 * statistics.latency_max << " ms over " << statistics.applied
              << " commands" << std::endl;
  }
}

void run_drive(const DriveOptions& options) {
  const EnvOptions env_options = drive_env_options(options);
  std::unique_ptr<Env> env = make_env(options.env_id, env_options);
  VelocityEnv& velocity = drive_velocity_env(*env, options.env_id);
  if (env->full_observation() == nullptr || !env->full_observation()->has_sim) {
    throw std::invalid_argument(
        "drive needs a simulator's ground truth to draw the robot (MuJoCo or Bullet), not " +
        options.env_id);
  }
  std::unique_ptr<Controller> controller =
      make_run_controller(options.env_id, options.controller, options.model, env_options, *env);
  const VelocityCommandRanges& ranges = velocity.command_ranges();
  DriveLimits limits;
  limits.max_forward_velocity = ranges.max_forward_velocity;
  limits.max_yaw_rate = ranges.max_yaw_rate;
  limits.height_command = ranges.height_command;
  limits.min_height = ranges.min_height;
  limits.max_height = ranges.max_height;
  auto drive = std::make_shared<DriveControl>(limits, options.rate);
  ViewSession session;
  session.title =
      options.env_id + ": " + (options.model.empty() ? options.controller : options.model);
  session.timestep = env->timestep();
  session.action_names = env->action_space().names;
  add_velocity_charts(session);
  LiveView view(options.view, std::move(session), drive);
  // Outputs last: a failure above leaves an existing record file as it was.
  std::optional<EpisodeRecorder> recorder;
  if (!options.record_path.empty()) {
    recorder.emplace(options.record_path);
    recorder->write_header(*env);
  }
  view.wait_for_browsers();
  std::cout << "drive: open the page and press the arrow keys or WASD (Q/Z raise and lower "
               "the base with a height command; or use a gamepad); "
               "Ctrl-C ends"
            << std::endl;
  DriveSummary summary;
  {
    const InterruptHandlers interrupts;
    DriveLoop loop(*env, velocity, *controller, view, *drive, recorder ? &*recorder : nullptr,
                   options.loop);
    summary = loop.run(interrupt_requested);
  }
  if (recorder) recorder->close();
  view.end("the drive is over");
  print_summary(summary, drive->statistics());
}

void add_drive_view_options(CLI::App& command, DriveOptions& options) {
  // The viewer's flags of every command; --host, --port, --wait and --speed, drive's first
  // spellings, still work.
  add_view_server_options(command, options.view, &kDrivenSpeed, true);
  command
      .add_option("--max-messages", options.rate.messages_per_second,
                  "Messages per second a page may send; more are refused")
      ->check(finite_range(1.0, 10000.0))
      ->capture_default_str();
}

}  // namespace

void add_drive_command(CLI::App& app) {
  auto options = std::make_shared<DriveOptions>();
  options->view.enabled = true;
  CLI::App* command = app.add_subcommand(
      "drive", "Drive a simulated robot from the browser (keyboard or gamepad), in real time");
  add_env_id_option(*command, options->env_id, "A velocity environment (Upkie-*-Velocity)")
      ->required();
  command
      ->add_option("--controller", options->controller,
                   "Built-in controller (lqr: the classical baseline), when no --model")
      ->capture_default_str();
  command->add_option("--model", options->model, "Trained model; replaces --controller")
      ->check(CLI::ExistingFile);
  add_env_option_option(*command, options->env_options, "; no time limit by default");
  add_seed_option(*command, options->loop.seed, "the first episode; episode e uses seed + e");
  command
      ->add_option("--record", options->record_path,
                   "Write one CSV row per step (replay it with `view` or `render`)")
      ->check(kNonEmptyPath);
  command
      ->add_option("--duration", options->loop.duration,
                   "Stop after this many simulated seconds; 0: at Ctrl-C")
      ->check(finite_range(0.0, 1e7))
      ->capture_default_str();
  command->add_option("--push-force", options->loop.push_force, "Force of a page's push [N]")
      ->check(finite_range(0.0, 500.0))
      ->capture_default_str();
  command->add_option("--push-duration", options->loop.push_duration, "Duration of a push [s]")
      ->check(finite_range(0.01, 2.0))
      ->capture_default_str();
  add_drive_view_options(*command, *options);
  command->callback([options] { run_drive(*options); });
}

}  // namespace upkie_rl::apps
