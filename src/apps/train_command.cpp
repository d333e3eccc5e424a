/// @file
/// `upkie-rl train`: PPO training from a YAML configuration, with a progress bar, a run
/// directory (config, TensorBoard events, CSV, checkpoints, final model) and resumption.

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/commands.hpp"
#include "cli/common_flags.hpp"
#include "cli/live_view.hpp"
#include "cli/option_checks.hpp"
#include "cli/progress_bar.hpp"
#include "cli/rendezvous_watchdog.hpp"
#include "cli/stuck_process_exit.hpp"
#include "envs/registry/env_factory.hpp"
#include "policy/crc32c.hpp"
#include "rl/distributed/communicator.hpp"
#include "rl/distributed/distributed_launch.hpp"
#include "rl/runs/training_config.hpp"
#include "rl/runs/training_run.hpp"
#include "vec/make_vector_env.hpp"

namespace upkie_rl::apps {

namespace {

struct TrainOptions {
  std::string config_path;
  std::vector<std::string> overrides;
  std::string run_dir;
  std::uint64_t seed = 0;
  CLI::Option* seed_option = nullptr;  // set when --seed was given
  std::string resume;
  bool force_run_dir = false;
  bool quiet = false;
  LiveViewOptions view;
  int view_env = 0;
  double distributed_timeout = 300.0;
};

/// The communicator of this process: alone, or one rank of the world the launcher's
/// variables describe (torchrun, srun).
std::shared_ptr<Communicator> join_world(const TrainOptions& options, DistributedLaunch& launch) {
  launch = distributed_launch_from_environment();
  if (!launch.distributed()) return nullptr;
  std::cerr << "rank " << launch.rank << " of " << launch.world_size << " (" << launch.source
            << "): meeting at " << launch.master_addr << ":" << launch.master_port << std::endl;
  CommunicatorOptions communicator_options;
  communicator_options.timeout =
      std::chrono::milliseconds(static_cast<std::int64_t>(1000.0 * options.distributed_timeout));
  // An abandoned rank (another aborted the run, or the store is gone) while this one's
  // main thread is stuck outside the collectives: no rank is left running.
  communicator_options.on_abandoned = exit_stuck_process;
  const std::string where = launch.master_addr + ":" + std::to_string(launch.master_port);
  RendezvousWatchdog watchdog(
      communicator_options.timeout + std::chrono::seconds(2),
      "rank " + std::to_string(launch.rank) + " of " + std::to_string(launch.world_size) +
          ": no rendezvous at " + where + " within --dist-timeout " +
          std::to_string(static_cast<int>(options.distributed_timeout)) +
          " s: is rank 0 running, is the port free of other programs, is each rank in [0, " +
          std::to_string(launch.world_size) + ") used once?");
  return connect_communicator(launch, communicator_options);
}

/// CRC-32C of the policy's weights: equal on every rank of a data-parallel run.
std::string weights_checksum(const TrainingRun& run) {
  const torch::Tensor& weights = run.ppo().policy().flat_parameters();
  char text[16];
  std::snprintf(text, sizeof(text), "%08x",
                crc32c({static_cast<const std::byte*>(weights.data_ptr()),
                        static_cast<std::size_t>(weights.numel()) * weights.element_size()}));
  return text;
}

/// One step of the viewed environment to the viewer.
void publish_step(LiveView& viewer, const Observation& observation, std::span<const float> action,
                  double reward, bool episode_ended, int& episode, int& step,
                  double& episode_return) {
  if (episode_ended) {
    viewer.start_episode(++episode);
    step = 0;
    episode_return = 0.0;
  } else {
    ++step;
    episode_return += reward;
  }
  viewer.publish(observation, step, episode_return, action);
}

/// Streams environment `index` of the run to a LiveView, as fast as the run goes: frames the
/// browsers cannot take are dropped, the training never waits.
std::unique_ptr<LiveView> view_training(const TrainOptions& options, TrainingRun& run) {
  const TrainingConfig& config = run.config();
  const double timestep = make_env(config.env_id, config.env_options)->timestep();
  auto view = std::make_unique<LiveView>(options.view,
                                         "training " + config.env_id + ": environment " +
                                             std::to_string(options.view_env) + " of " +
                                             std::to_string(config.num_envs),
                                         timestep, run.ppo().env().action_space().names);
  LiveView* viewer = view.get();
  run.observe_env(static_cast<std::size_t>(options.view_env),
                  [viewer, episode = 0, step = 0, episode_return = 0.0, failed = false](
                      const Observation& observation, std::span<const float> action, double reward,
                      bool episode_ended) mutable {
                    if (failed) return;
                    // The training never stops because of the viewer: its failure is
                    // reported once and the viewer is left behind.
                    try {
                      publish_step(*viewer, observation, action, reward, episode_ended, episode,
                                   step, episode_return);
                    } catch (const std::exception& error) {
                      failed = true;
                      std::cerr << "viewer: " << error.what() << "; the training goes on without it"
                                << std::endl;
                    }
                  });
  viewer->wait_for_browsers();
  return view;
}

std::filesystem::path default_run_dir(const std::string& config_path) {
  return std::filesystem::path("runs") /
         (std::filesystem::path(config_path).stem().string() + "-" + local_timestamp());
}

/// The run: resumed from --resume's checkpoint, or new from --config, --set and --seed.
std::unique_ptr<TrainingRun> open_run(const TrainOptions& options,
                                      const std::shared_ptr<Communicator>& communicator) {
  if (!options.resume.empty()) {
    if (!options.config_path.empty() || !options.overrides.empty() ||
        options.seed_option->count() > 0) {
      throw std::invalid_argument(
          "--resume continues the checkpoint's own configuration; it cannot be combined with "
          "--config, --set or --seed");
    }
    std::optional<std::filesystem::path> run_dir;
    if (!options.run_dir.empty()) run_dir = options.run_dir;
    std::unique_ptr<TrainingRun> run =
        TrainingRun::resume(options.resume, run_dir, communicator, options.force_run_dir);
    std::cerr << "resuming " << options.resume << " at " << run->ppo().num_timesteps() << " steps"
              << std::endl;
    return run;
  }
  if (options.config_path.empty()) {
    throw std::invalid_argument("train needs --config FILE (or --resume CHECKPOINT)");
  }
  TrainingConfig config = load_training_config(options.config_path);
  apply_overrides(config, options.overrides);
  if (options.seed_option->count() > 0) config.seed = options.seed;
  config.validate();
  const std::filesystem::path run_dir = options.run_dir.empty()
                                            ? default_run_dir(options.config_path)
                                            : std::filesystem::path(options.run_dir);
  return std::make_unique<TrainingRun>(config, run_dir, communicator, options.force_run_dir);
}

/// The line on stderr that says what is trained, on how many ranks.
void announce_training(const DistributedLaunch& launch, const TrainingRun& run) {
  const TrainingConfig& config = run.config();
  if (launch.distributed()) {
    // ppo.n_steps and batch_size are per rank: each rank collects n_steps and each
    // optimiser step averages the gradients of world_size minibatches.
    std::cerr << "rank " << launch.rank << ": DD-PPO over " << launch.world_size
              << " ranks: " << launch.world_size << " x " << config.num_envs
              << " envs, global n_steps " << launch.world_size * config.ppo.n_steps
              << ", global minibatch " << launch.world_size * config.ppo.batch_size << ", "
              << with_thousands(config.ppo.total_timesteps) << " steps in all"
              << (run.writes_outputs() ? ", run directory " + run.run_dir().string() : "")
              << std::endl;
  } else {
    std::cerr << "training " << config.env_id << " with PPO: " << config.num_envs << " envs, "
              << with_thousands(config.ppo.total_timesteps) << " steps, run directory "
              << run.run_dir().string() << std::endl;
  }
}

/// The summary of the run on stdout: speed, where the time went, the files written. The
/// time in all-reduces is shown for a world of several ranks: alone, the collectives do
/// nothing and their timer would only measure itself.
void report_training(const TrainingRun& run, const TrainingProgress& last,
                     const std::filesystem::path& model, bool distributed) {
  const PpoTimings& timings = run.ppo().timings();
  const double accounted = timings.env_seconds + timings.inference_seconds + timings.update_seconds;
  std::cout << "trained " << with_thousands(last.timesteps) << " steps in "
            << format_duration(last.elapsed_seconds) << " ("
            << with_thousands(static_cast<std::int64_t>(last.steps_per_second))
            << " steps/s); mean return of the last 100 episodes " << last.mean_return
            << ", mean length " << last.mean_length << std::endl;
  std::cout << "time: environments " << timings.env_seconds << " s, policy inference "
            << timings.inference_seconds << " s, updates " << timings.update_seconds << " s";
  if (distributed) std::cout << " (of which all-reduces " << timings.communication_seconds << " s)";
  std::cout << ", other " << std::max(0.0, last.elapsed_seconds - accounted) << " s" << std::endl;
  std::cout << "run directory: " << run.run_dir().string() << std::endl;
  std::cout << "final model: " << model.string() << std::endl;
  std::cout << "TorchScript policy: " << run.torchscript_path().string() << std::endl;
}

void run_train(const TrainOptions& options) {
  DistributedLaunch launch;
  const std::shared_ptr<Communicator> communicator = join_world(options, launch);
  const std::unique_ptr<TrainingRun> run = open_run(options, communicator);
  const TrainingConfig& config = run->config();
  const bool writer = run->writes_outputs();
  announce_training(launch, *run);

  std::unique_ptr<LiveView> view;
  if (options.view.enabled && writer) view = view_training(options, *run);
  ProgressBar bar(config.ppo.total_timesteps);
  TrainingProgress last;
  const std::filesystem::path model = run->train([&](const TrainingProgress& progress) {
    last = progress;
    if (!options.quiet && writer)
      bar.update(progress.timesteps, progress.steps_per_second, progress.mean_return);
  });
  if (!options.quiet && writer) bar.finish();
  if (view) view->end("the training is over");

  if (launch.distributed()) {
    std::cout << "rank " << launch.rank << ": weights checksum " << weights_checksum(*run)
              << std::endl;
  }
  if (writer) report_training(*run, last, model, launch.distributed());
}

}  // namespace

void add_train_command(CLI::App& app) {
  auto options = std::make_shared<TrainOptions>();
  CLI::App* command = app.add_subcommand(
      "train", "Train a policy with PPO from a YAML configuration (configs/pendulum.yaml)");
  command->add_option("--config", options->config_path, "Training configuration (YAML)")
      ->check(CLI::ExistingFile);
  command->add_option("--set", options->overrides,
                      "Override a configuration key, e.g. --set ppo.total_timesteps=200000 "
                      "(repeatable)");
  command
      ->add_option("--run-dir", options->run_dir,
                   "Run directory (default: runs/<config name>-<date>-<time>; with --resume, "
                   "the checkpoint's run)")
      ->check(kNonEmptyPath);
  options->seed_option = add_seed_option(
      *command, options->seed, "the run (overrides the config's seed)", DefaultInHelp::kHidden);
  command->add_option("--resume", options->resume, "Continue a run from one of its checkpoints")
      ->check(CLI::ExistingFile);
  command->add_flag("--force-run-dir", options->force_run_dir,
                    "Train in --run-dir even when it is a non-empty directory that is not "
                    "an upkie-rl run (its config.yaml and progress.csv are replaced) or, with "
                    "--resume, another run's");
  command->add_flag("--quiet", options->quiet, "No progress bar");
  options->view.speed = 0.0;  // the training never waits for the viewer
  add_live_view_options(*command, options->view, false);
  command
      ->add_option("--dist-timeout", options->distributed_timeout,
                   "Distributed runs (torchrun, srun): seconds a rank waits for the others "
                   "before it stops with an error")
      ->check(finite_range(1.0, 86400.0))
      ->capture_default_str();
  command->add_option("--view-env", options->view_env, "Environment of the run --view shows")
      ->check(finite_range(0, static_cast<double>(kMaxVectorEnvs - 1)))
      ->capture_default_str();
  command->callback([options] { run_train(*options); });
}

}  // namespace upkie_rl::apps
