/// @file
/// `upkie-rl rollout`: runs episodes of an environment with a controller and reports their
/// returns (the seed's rollout_policy.py).

#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "apps/commands.hpp"
#include "apps/controller_option.hpp"
#include "apps/option_checks.hpp"
#include "apps/record_file.hpp"
#include "apps/live_view.hpp"
#include "apps/policy_controller.hpp"
#include "apps/video_recorder.hpp"
#include "envs/builtin_controllers.hpp"
#include "envs/episode_runner.hpp"
#include "envs/evaluation_start.hpp"
#include "envs/registry.hpp"
#include "sim/observation_dict.hpp"

namespace upkie_rl::apps {

namespace {

struct RolloutOptions {
  std::string env_id;
  std::string controller = "zero";
  std::string model;  // a trained policy (`upkie-rl train`), replaces --controller
  int episodes = 1;
  std::uint64_t seed = 0;
  int max_steps = 1000;
  std::vector<std::string> env_options;
  std::string record_path;
  bool json = false;
  bool info = false;
  bool exact_start = false;
  VideoOptions video;
  LiveViewOptions view;
};

/// Offers the env's state to the video; the env must have a simulator's ground truth.
void add_video_frame(VideoRecorder& video, const Env& env, double episode_return) {
  const Observation* full = env.full_observation();
  if (full == nullptr || !full->has_sim) {
    throw std::runtime_error("--video needs a simulated environment (Bullet, MuJoCo or Mock)");
  }
  video.add(robot_pose(*full), full->time, episode_return, full->base_orientation.pitch);
}

std::unique_ptr<Controller> make_rollout_controller(const RolloutOptions& options,
                                                    const EnvOptions& env_options, const Env& env) {
  if (!options.model.empty()) return make_policy_controller(options.model, env);
  const std::string spec =
      resolve_controller_spec(options.controller, design_env_factory(options.env_id, env_options));
  if (spec != options.controller) std::cout << options.controller << ": " << spec << std::endl;
  return make_builtin_controller(spec, env);
}

void run_rollout(const RolloutOptions& options) {
  EnvOptions env_options = parse_env_options(options.env_options);
  if (!options.model.empty()) {
    env_options = options_for_model(options.model, options.env_id, env_options);
    if (!env_options.empty()) {
      std::cout << "environment options: " << format_env_options(env_options) << std::endl;
    }
  }
  if (!options.exact_start) {
    const EnvOptions start = evaluation_start_options(options.env_id, env_options);
    if (!start.empty()) {
      std::cout << "random initial state: " << format_env_options(start)
                << " (--exact-start: the environment's own)" << std::endl;
    }
    env_options.insert(env_options.end(), start.begin(), start.end());
  }
  std::unique_ptr<Env> env = make_env(options.env_id, env_options);
  std::unique_ptr<Controller> controller = make_rollout_controller(options, env_options, *env);
  std::optional<LiveView> view;
  if (options.view.enabled) {
    if (env->full_observation() == nullptr) {
      throw std::runtime_error("--view needs an environment with full observations");
    }
    view.emplace(
        options.view,
        options.env_id + ": " + (options.model.empty() ? options.controller : options.model),
        env->timestep(), env->action_space().names);
  }
  // Outputs last, once everything else is known to work: a failure above (a busy port, a
  // bad controller) leaves an existing record file as it was. Bad paths are still refused
  // before the first episode.
  std::optional<EpisodeRecorder> recorder;
  if (!options.record_path.empty()) recorder.emplace(options.record_path);
  std::optional<VideoRecorder> video;
  if (!options.video.path.empty()) video.emplace(RobotModel::default_model(), options.video);
  if (recorder) recorder->write_header(*env);
  if (view) view->wait_for_browsers();

  std::vector<float> observation(env->observation_space().size());
  std::vector<float> action(env->action_space().size());
  std::vector<double> returns;
  std::vector<int> lengths;
  for (int episode = 0; episode < options.episodes; ++episode) {
    env->reset(options.seed + static_cast<std::uint64_t>(episode), observation);
    controller->reset();
    double total = 0.0;
    if (video) {
      video->start_episode(episode);
      add_video_frame(*video, *env, total);
    }
    int length = 0;
    const char* ending = "max-steps";
    if (view) view->start_episode(episode);
    while (length < options.max_steps) {
      controller->act(observation, action);
      if (view) view->publish(*env->full_observation(), length, total, action);
      if (recorder) recorder->before_step(*env, observation);
      const StepResult result = env->step(action, observation);
      if (recorder) recorder->after_step(episode, length, action, result);
      total += result.reward;
      ++length;
      if (video) add_video_frame(*video, *env, total);
      if (result.terminated || result.truncated) {
        ending = result.terminated ? "terminated" : "truncated";
        break;
      }
    }
    returns.push_back(total);
    lengths.push_back(length);
    std::cout << "episode " << episode << ": return " << total << ", length " << length << " ("
              << ending << ")" << std::endl;
    if (options.info) {
      const Observation* full = env->full_observation();
      std::cout << "info: " << (full ? observation_to_json(*full).dump() : "{}") << std::endl;
    }
  }
  if (recorder) recorder->close();
  if (view) view->end("the rollout is over (" + std::to_string(options.episodes) + " episodes)");
  if (video) {
    video->close();
    std::cout << "video " << options.video.path.string() << ": " << video->frames() << " frames at "
              << options.video.fps << " frames/s" << std::endl;
  }

  std::vector<EpisodeOutcome> outcomes;
  for (std::size_t e = 0; e < returns.size(); ++e) outcomes.push_back({returns[e], lengths[e]});
  const EpisodeSummary summary = summarize_episodes(outcomes);
  const double mean = summary.mean_return;
  const double mean_length = summary.mean_length;
  const double std_return = summary.std_return;
  const std::string identical = identical_episodes_warning(returns, lengths);
  if (!identical.empty()) std::cerr << "upkie-rl: warning: " << identical << std::endl;
  std::cout << "mean return " << mean << " +- " << std_return << " over " << returns.size()
            << " episodes, mean length " << mean_length << std::endl;
  if (options.json) {
    const nlohmann::json summary = {{"episodes", returns.size()}, {"mean_return", mean},
                                    {"std_return", std_return},   {"mean_length", mean_length},
                                    {"returns", returns},         {"lengths", lengths}};
    std::cout << summary.dump() << std::endl;
  }
}

}  // namespace

void add_rollout_command(CLI::App& app) {
  auto options = std::make_shared<RolloutOptions>();
  CLI::App* command = app.add_subcommand(
      "rollout", "Run episodes of an environment with a controller and report their returns");
  command->add_option("--env", options->env_id, "Environment id (see `upkie-rl envs`)")->required();
  command->add_option("--controller", options->controller, kControllerHelp)->capture_default_str();
  command
      ->add_option("--model", options->model,
                   "Trained model (model_*.ckpt or a checkpoint of `upkie-rl train`): "
                   "deterministic policy with its frozen normalisation; replaces --controller")
      ->check(CLI::ExistingFile);
  command->add_option("--episodes", options->episodes, "Number of episodes")
      ->check(CLI::Range(1, 1'000'000))
      ->capture_default_str();
  command->add_option("--seed", options->seed, "Seed of the first episode; episode e uses seed + e")
      ->capture_default_str();
  command
      ->add_option("--max-steps", options->max_steps,
                   "Also end an episode after this many steps (the env's own limit applies)")
      ->check(CLI::Range(1, 1'000'000'000))
      ->capture_default_str();
  command->add_option("--env-option", options->env_options,
                      "Environment option key=value (repeatable)");
  command->add_option("--record", options->record_path, "Write one CSV row per step to this file")
      ->check(kNonEmptyPath);
  add_video_options(*command, options->video);
  add_live_view_options(*command, options->view, true);
  command->add_flag("--json", options->json, "Print the summary as JSON on the last line");
  command->add_flag("--exact-start", options->exact_start, kExactStartHelp);
  command->add_flag("--info", options->info,
                    "Print each episode's last info (the full observation dictionary)");
  command->callback([options] { run_rollout(*options); });
}

}  // namespace upkie_rl::apps
