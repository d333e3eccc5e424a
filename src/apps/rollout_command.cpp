/// @file
/// `upkie-rl rollout`: runs episodes of an environment with a controller and reports their
/// returns (the seed's rollout_policy.py).

#include <array>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "apps/commands.hpp"
#include "cli/command_error.hpp"
#include "cli/common_flags.hpp"
#include "cli/controller_choice.hpp"
#include "cli/controller_option.hpp"
#include "cli/gnuplot_figure.hpp"
#include "cli/live_view.hpp"
#include "cli/option_checks.hpp"
#include "cli/tracking_report.hpp"
#include "cli/velocity_view.hpp"
#include "cli/video_recorder.hpp"
#include "envs/evaluation/episode_runner.hpp"
#include "envs/evaluation/evaluation_start.hpp"
#include "envs/kinds/velocity_env.hpp"
#include "envs/records/record_file.hpp"
#include "envs/registry/env_factory.hpp"
#include "envs/registry/env_settings.hpp"
#include "envs/tasks/velocity_command_schedule.hpp"
#include "sim/observation_dict.hpp"

namespace upkie_rl::apps {

namespace {

struct RolloutOptions {
  std::string env_id;
  std::string controller = "zero";
  std::string model;  // a trained policy (`upkie-rl train`), replaces --controller
  int episodes = 1;
  std::uint64_t seed = 0;
  int max_steps = kDefaultMaxSteps;
  std::vector<std::string> env_options;
  std::string record_path;
  bool json = false;
  bool info = false;
  bool exact_start = false;
  std::string commands_path;  // velocity tasks: scripted commands (time, vx, wz)
  std::string plot_prefix;    // velocity tasks: commanded vs measured figures of episode 0
  VideoOptions video;
  LiveViewOptions view;
};

/// Offers the env's state to the video; the env must have a simulator's ground truth.
void add_video_frame(VideoRecorder& video, const Env& env, double episode_return) {
  const Observation* full = env.full_observation();
  if (full == nullptr || !full->has_sim) {
    throw CommandError("--video needs a simulated environment (Bullet, MuJoCo or Mock)");
  }
  const VelocityEnv* velocity = find_velocity_env(env);
  if (velocity != nullptr) {
    const BaseVelocity measured = velocity->measured_velocity();
    video.add(robot_pose(*full), full->time, episode_return, full->base_orientation.pitch,
              &velocity->command(), &measured);
    return;
  }
  video.add(robot_pose(*full), full->time, episode_return, full->base_orientation.pitch);
}

/// Targets, commanded (acceleration-limited) and measured velocities of one episode, for
/// --plot.
struct VelocityTrace {
  std::vector<double> time;
  std::vector<double> target_forward, commanded_forward, measured_forward;
  std::vector<double> target_yaw, commanded_yaw, measured_yaw;
  std::vector<double> target_height, commanded_height, measured_height;
  bool height_command = false;

  void add(double t, const VelocityEnv& env) {
    height_command = env.command_ranges().height_command;
    const VelocityCommand& target = env.last_step_target();
    const VelocityCommand& command = env.last_step_command();
    const BaseVelocity velocity = env.measured_velocity();
    time.push_back(t);
    target_forward.push_back(target.forward_velocity);
    commanded_forward.push_back(command.forward_velocity);
    measured_forward.push_back(velocity.forward_velocity);
    target_yaw.push_back(target.yaw_rate);
    commanded_yaw.push_back(command.yaw_rate);
    measured_yaw.push_back(velocity.yaw_rate);
    target_height.push_back(target.height);
    commanded_height.push_back(command.height);
    measured_height.push_back(velocity.height);
  }

  /// <prefix>_forward_velocity.png and <prefix>_yaw_rate.png (and <prefix>_height.png with a
  /// height command).
  void draw(const std::string& prefix, const std::string& title) const {
    const auto figure = [&](const char* name, const char* label, const std::vector<double>& target,
                            const std::vector<double>& wanted,
                            const std::vector<double>& measured) {
      CurvesFigure out;
      out.output = prefix + "_" + name + ".png";
      out.title = title;
      out.x_label = "time [s]";
      out.y_label = label;
      out.curves = {
          {"target", time, target}, {"commanded", time, wanted}, {"measured", time, measured}};
      draw_curves_figure(out);
      std::cout << "figure " << out.output.string() << std::endl;
    };
    figure("forward_velocity", "forward velocity [m/s]", target_forward, commanded_forward,
           measured_forward);
    figure("yaw_rate", "yaw rate [rad/s]", target_yaw, commanded_yaw, measured_yaw);
    if (height_command) {
      figure("height", "base height [m]", target_height, commanded_height, measured_height);
    }
  }
};

/// What a rollout runs and writes: the environment and its controller, and the optional
/// velocity-task pieces, live view, record file and video.
struct Rollout {
  EnvOptions env_options;
  std::unique_ptr<Env> env;
  std::unique_ptr<Controller> controller;
  VelocityEnv* velocity = nullptr;  // In env, for a velocity task.
  std::optional<VelocityCommandSchedule> schedule;
  VelocityTrace trace;
  std::optional<LiveView> view;
  std::optional<EpisodeRecorder> recorder;
  std::optional<VideoRecorder> video;
  std::string start_words;  ///< Which start the episodes had ("from random starts", ...).
};

/// The environment (from a random evaluation start unless --exact-start), its controller
/// and the velocity task's command schedule; refuses options that do not fit.
void make_env_and_controller(const RolloutOptions& options, Rollout& rollout) {
  rollout.env_options =
      run_env_options(options.env_id, options.model, parse_env_options(options.env_options));
  EnvOptions start;
  if (!options.exact_start) {
    start = evaluation_start_options(options.env_id, rollout.env_options);
    rollout.env_options.insert(rollout.env_options.end(), start.begin(), start.end());
  }
  rollout.env = make_env(options.env_id, rollout.env_options);
  rollout.start_words =
      evaluation_start_words(options.env_id, rollout.env_options, options.exact_start);
  // Printed once the options are known good: a refused option is the only line.
  if (!start.empty()) {
    std::cout << "random initial state: " << format_env_options(start)
              << " (--exact-start: the environment's own)" << std::endl;
  }
  rollout.controller = make_run_controller(options.env_id, options.controller, options.model,
                                           rollout.env_options, *rollout.env);
  rollout.velocity = find_velocity_env(*rollout.env);
  if (rollout.velocity == nullptr &&
      (!options.commands_path.empty() || !options.plot_prefix.empty())) {
    throw std::invalid_argument(
        "--commands and --plot need a velocity task (Upkie-*-Velocity), not " + options.env_id);
  }
  if (!options.commands_path.empty()) {
    rollout.schedule.emplace(
        VelocityCommandSchedule::load(options.commands_path, rollout.velocity->command_ranges()));
  }
  if (!options.plot_prefix.empty()) find_gnuplot();  // refuse at once, not after the work
}

/// The live view, the record file and the video, in that order.
void open_outputs(const RolloutOptions& options, Rollout& rollout) {
  Env& env = *rollout.env;
  if (options.view.enabled) {
    if (env.full_observation() == nullptr) {
      throw CommandError("--view needs an environment with full observations");
    }
    ViewSession session;
    session.title =
        options.env_id + ": " + (options.model.empty() ? options.controller : options.model);
    session.timestep = env.timestep();
    session.action_names = env.action_space().names;
    if (rollout.velocity != nullptr) add_velocity_charts(session);
    rollout.view.emplace(options.view, std::move(session));
  }
  // Outputs last, once everything else is known to work: a failure above (a busy port, a
  // bad controller) leaves an existing record file as it was. Bad paths are still refused
  // before the first episode.
  if (!options.record_path.empty()) rollout.recorder.emplace(options.record_path);
  if (!options.video.path.empty()) {
    // The frames show the floor the episodes ran on.
    VideoOptions video = options.video;
    video.bumps =
        parse_env_settings(parse_env_id(options.env_id), options.env_id, rollout.env_options).bumps;
    rollout.video.emplace(RobotModel::default_model(), video);
  }
  if (rollout.recorder) rollout.recorder->write_header(env);
  if (rollout.view) rollout.view->wait_for_browsers();
}

/// Buffers of the episodes' loop, made once.
struct RolloutBuffers {
  std::vector<float> observation;
  std::vector<float> action;
  std::array<double, kVelocityViewFields> velocity_fields{};
};

/// Publishes the step about to be taken to the live view.
void publish_step(Rollout& rollout, RolloutBuffers& buffers, int length, double total) {
  std::span<const double> extra;
  if (rollout.velocity != nullptr) {
    write_velocity_fields(rollout.velocity->command(), rollout.velocity->measured_velocity(),
                          buffers.velocity_fields);
    extra = buffers.velocity_fields;
  }
  rollout.view->publish(*rollout.env->full_observation(), length, total, buffers.action, extra);
}

/// Runs episode `episode` to its end or options.max_steps and prints its line.
EpisodeOutcome roll_out_episode(const RolloutOptions& options, Rollout& rollout,
                                RolloutBuffers& buffers, int episode) {
  Env& env = *rollout.env;
  VelocityEnv* velocity = rollout.velocity;
  if (rollout.schedule) velocity->set_command_override(rollout.schedule->at(0.0));
  env.reset(options.seed + static_cast<std::uint64_t>(episode), buffers.observation);
  rollout.controller->reset();
  EpisodeOutcome outcome;
  double total = 0.0;
  if (rollout.video) {
    rollout.video->start_episode(episode);
    add_video_frame(*rollout.video, env, total);
  }
  int length = 0;
  const char* ending = "max-steps";
  if (rollout.view) rollout.view->start_episode(episode);
  while (length < options.max_steps) {
    rollout.controller->act(buffers.observation, buffers.action);
    if (rollout.view) publish_step(rollout, buffers, length, total);
    if (rollout.recorder) rollout.recorder->before_step(env, buffers.observation);
    // The observation this step returns shows the command of the next one.
    if (rollout.schedule) {
      velocity->set_command_override(rollout.schedule->at((length + 1) * env.timestep()));
    }
    const StepResult result = env.step(buffers.action, buffers.observation);
    if (rollout.recorder) rollout.recorder->after_step(episode, length, buffers.action, result);
    total += result.reward;
    ++length;
    if (velocity != nullptr) {
      outcome.tracking.add(*velocity, result.terminated);
      if (episode == 0 && !options.plot_prefix.empty()) {
        rollout.trace.add(length * env.timestep(), *velocity);
      }
    }
    if (rollout.video) add_video_frame(*rollout.video, env, total);
    if (result.terminated || result.truncated) {
      ending = result.terminated ? "terminated" : "truncated";
      outcome.terminated = result.terminated;
      break;
    }
  }
  outcome.total_reward = total;
  outcome.length = length;
  std::cout << "episode " << episode << ": return " << total << ", length " << length << " ("
            << ending << ")" << std::endl;
  if (options.info) {
    const Observation* full = env.full_observation();
    std::cout << "info: " << (full ? observation_to_json(*full).dump() : "{}") << std::endl;
  }
  return outcome;
}

/// The summary of the episodes: mean return and length, tracking errors, --json.
void report_episodes(const RolloutOptions& options, const std::vector<EpisodeOutcome>& outcomes,
                     const std::string& start_words) {
  std::vector<double> returns;
  std::vector<int> lengths;
  for (const EpisodeOutcome& outcome : outcomes) {
    returns.push_back(outcome.total_reward);
    lengths.push_back(outcome.length);
  }
  const EpisodeSummary summary = summarize_episodes(outcomes);
  const double mean = summary.mean_return;
  const double mean_length = summary.mean_length;
  const double std_return = summary.std_return;
  const std::string identical = identical_episodes_warning(returns, lengths);
  if (!identical.empty()) std::cerr << "upkie-rl: warning: " << identical << std::endl;
  std::cout << "mean return " << mean << " +- " << std_return << " over " << returns.size()
            << " episodes " << start_words << ", mean length " << mean_length << std::endl;
  const std::string tracking = tracking_text(summary);
  if (!tracking.empty()) std::cout << tracking << std::endl;
  if (options.json) {
    nlohmann::json json = {{"episodes", returns.size()}, {"mean_return", mean},
                           {"std_return", std_return},   {"mean_length", mean_length},
                           {"returns", returns},         {"lengths", lengths},
                           {"start", start_words}};
    add_tracking_json(json, summary);
    std::cout << json.dump() << std::endl;
  }
}

void run_rollout(const RolloutOptions& options) {
  Rollout rollout;
  make_env_and_controller(options, rollout);
  open_outputs(options, rollout);
  RolloutBuffers buffers;
  buffers.observation.resize(rollout.env->observation_space().size());
  buffers.action.resize(rollout.env->action_space().size());
  std::vector<EpisodeOutcome> outcomes;
  for (int episode = 0; episode < options.episodes; ++episode) {
    outcomes.push_back(roll_out_episode(options, rollout, buffers, episode));
  }
  if (rollout.recorder) rollout.recorder->close();
  if (rollout.view) {
    rollout.view->end("the rollout is over (" + std::to_string(options.episodes) + " episodes)");
  }
  if (rollout.video) {
    rollout.video->close();
    std::cout << "video " << options.video.path.string() << ": " << rollout.video->frames()
              << " frames at " << options.video.fps << " frames/s" << std::endl;
  }
  if (!options.plot_prefix.empty()) {
    rollout.trace.draw(options.plot_prefix,
                       options.env_id + ", episode 0: " +
                           (options.model.empty() ? options.controller : options.model));
  }
  report_episodes(options, outcomes, rollout.start_words);
}

}  // namespace

void add_rollout_command(CLI::App& app) {
  auto options = std::make_shared<RolloutOptions>();
  CLI::App* command = app.add_subcommand(
      "rollout", "Run episodes of an environment with a controller and report their returns");
  add_env_id_option(*command, options->env_id)->required();
  command->add_option("--controller", options->controller, kControllerHelp)->capture_default_str();
  command
      ->add_option("--model", options->model,
                   "Trained model (model_*.ckpt or a checkpoint of `upkie-rl train`): "
                   "deterministic policy with its frozen normalisation; replaces --controller")
      ->check(CLI::ExistingFile);
  add_episodes_option(*command, options->episodes);
  add_seed_option(*command, options->seed, "the first episode; episode e uses seed + e");
  add_max_steps_option(*command, options->max_steps, "its line then ends with \"(max-steps)\"");
  add_env_option_option(*command, options->env_options);
  command->add_option("--record", options->record_path, "Write one CSV row per step to this file")
      ->check(kNonEmptyPath);
  add_video_options(*command, options->video);
  add_live_view_options(*command, options->view, true);
  command
      ->add_option("--commands", options->commands_path,
                   "Velocity tasks: scripted commands, a CSV of rows time,vx,wz ([s], [m/s], "
                   "[rad/s]), each held until the next row's time")
      ->check(CLI::ExistingFile);
  command
      ->add_option("--plot", options->plot_prefix,
                   "Velocity tasks: draw commanded against measured velocities of episode 0 "
                   "in PREFIX_forward_velocity.png and PREFIX_yaw_rate.png")
      ->check(kNonEmptyPath);
  add_json_flag(*command, options->json);
  command->add_flag("--exact-start", options->exact_start, kExactStartHelp);
  command->add_flag("--info", options->info,
                    "Print each episode's last info (the full observation dictionary)");
  command->callback([options] { run_rollout(*options); });
}

}  // namespace upkie_rl::apps
