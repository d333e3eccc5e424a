/// @file
/// `upkie-rl sweep`: independent trainings over seeds and a grid of settings, run here a
/// bounded number at a time or handed one by one to a cluster's launcher, then one summary
/// of their final evaluations and a figure of their return curves.

#include <csignal>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "apps/commands.hpp"
#include "cli/child_process.hpp"
#include "cli/command_error.hpp"
#include "cli/common_flags.hpp"
#include "cli/interrupt_handlers.hpp"
#include "cli/option_checks.hpp"
#include "cli/policy_controller.hpp"
#include "cli/progress_bar.hpp"
#include "cli/sweep_outcome.hpp"
#include "cli/sweep_summary.hpp"
#include "envs/evaluation/episode_runner.hpp"
#include "envs/registry/env_factory.hpp"
#include "rl/logging/scalar_csv_writer.hpp"
#include "rl/runs/sweep_plan.hpp"
#include "rl/runs/training_run.hpp"

namespace upkie_rl::apps {

namespace {

struct SweepOptions {
  std::string directory;  // an existing sweep
  std::string config_path;
  std::string seeds;
  std::vector<std::string> axes;
  std::string out;
  int jobs = 0;  // 0: one per env.threads of the cores
  int evaluation_episodes = 10;
  bool plan_only = false;
  int run_index = -1;
  bool summary_only = false;
};

std::string plural(std::size_t count, const std::string& noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

/// The last file of `directory` whose name starts with `prefix` and ends with ".ckpt"
/// (checkpoint names sort by their zero-padded step count, model names by date).
std::optional<std::filesystem::path> last_file(const std::filesystem::path& directory,
                                               const std::string& prefix) {
  std::optional<std::filesystem::path> last;
  if (!std::filesystem::is_directory(directory)) return last;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0 || entry.path().extension() != ".ckpt") continue;
    if (!last || name > last->filename().string()) last = entry.path();
  }
  return last;
}

/// Moves a run directory that holds no checkpoint aside (nothing is deleted), so that the
/// run starts again in a fresh one.
void set_aside(const std::filesystem::path& run_dir) {
  for (int n = 1;; ++n) {
    const std::filesystem::path aside = run_dir.string() + ".incomplete-" + std::to_string(n);
    if (std::filesystem::exists(aside)) continue;
    std::filesystem::rename(run_dir, aside);
    std::cout << "moved the unfinished " << run_dir.string() << " (no checkpoint) to "
              << aside.string() << std::endl;
    return;
  }
}

/// Trains run `run` (or continues it from its last checkpoint) unless its final model
/// exists, then evaluates that model and writes evaluation.json.
void run_one(const Sweep& sweep, const SweepRun& run) {
  const std::filesystem::path run_dir = sweep.run_dir(run);
  if (read_sweep_outcome(run_dir)) {
    std::cout << "run " << run.name << " is done already" << std::endl;
    return;
  }
  const TrainingConfig config = sweep_run_config(sweep.base, run);
  SweepOutcome outcome;
  outcome.training_mean_return = std::nan("");
  std::optional<std::filesystem::path> model = last_file(run_dir, "model_");
  if (!model) {
    std::unique_ptr<TrainingRun> training;
    if (const auto checkpoint = last_file(run_dir / "checkpoints", "checkpoint_")) {
      training = TrainingRun::resume(*checkpoint, run_dir);
      std::cout << "run " << run.name << ": resuming " << checkpoint->string() << std::endl;
    } else {
      if (std::filesystem::exists(run_dir)) set_aside(run_dir);
      training = std::make_unique<TrainingRun>(config, run_dir);
      std::cout << "run " << run.name << ": training " << config.env_id << ", "
                << with_thousands(config.ppo.total_timesteps) << " steps, seed " << run.seed
                << (run.overrides.empty() ? "" : ", " + sweep_group_label(run)) << std::endl;
    }
    ProgressBar bar(config.ppo.total_timesteps, stdout);
    model = training->train([&](const TrainingProgress& progress) {
      bar.update(progress.timesteps, progress.steps_per_second, progress.mean_return);
      outcome.train_seconds = progress.elapsed_seconds;
    });
    bar.finish();
  }
  // The training figures of the run, from its log (whichever process trained it).
  const ScalarTable progress = read_scalar_csv(run_dir / "progress.csv");
  if (!progress.rows.empty()) {
    outcome.timesteps =
        static_cast<std::int64_t>(progress.rows.back()[progress.index("time/total_timesteps")]);
    outcome.training_mean_return = progress.rows.back()[progress.index("rollout/ep_rew_mean")];
  }
  outcome.model = model->filename().string();

  std::unique_ptr<Env> env = make_env(config.env_id, config.env_options);
  std::unique_ptr<Controller> policy = make_policy_controller(*model, *env);
  std::vector<float> observation(env->observation_space().size());
  std::vector<float> action(env->action_space().size());
  std::vector<EpisodeOutcome> episodes;
  for (int episode = 0; episode < sweep.plan.evaluation_episodes; ++episode) {
    episodes.push_back(run_episode(*env, *policy,
                                   sweep.plan.evaluation_seed + static_cast<std::uint64_t>(episode),
                                   sweep.plan.evaluation_max_steps, observation, action));
  }
  outcome.evaluation = summarize_episodes(episodes);
  write_sweep_outcome(run_dir, outcome);
  std::cout << "run " << run.name << ": evaluation return " << std::fixed << std::setprecision(1)
            << outcome.evaluation.mean_return << " +- " << outcome.evaluation.std_return
            << std::defaultfloat << " over " << outcome.evaluation.episodes << " episodes ("
            << outcome.evaluation.successes << " survived), mean length "
            << outcome.evaluation.mean_length << std::endl;
}

/// Prints how the child process of `run` ended; false when it failed (not stopped by
/// an interrupt). `stamp`: "[elapsed]"; `progress`: "[elapsed] finished/pending".
bool report_exit(const Sweep& sweep, const SweepRun& run, const ChildExit& child, bool stopping,
                 const std::string& stamp, const std::string& progress) {
  const std::optional<SweepOutcome> outcome =
      child.exit_code == 0 ? read_sweep_outcome(sweep.run_dir(run)) : std::nullopt;
  if (outcome) {
    std::cout << progress << " done " << run.name << ": evaluation return " << std::fixed
              << std::setprecision(1) << outcome->evaluation.mean_return << " +- "
              << outcome->evaluation.std_return << std::defaultfloat << std::endl;
    return true;
  }
  if (stopping) {
    std::cout << stamp << " stopped " << run.name << std::endl;
    return true;
  }
  std::cout << progress << " FAILED " << run.name << " (exit " << child.exit_code
            << "): " << last_line(sweep.log_path(run)) << std::endl;
  return false;
}

/// Runs the unfinished runs of the sweep as child processes (`upkie-rl sweep DIR --run I`),
/// `jobs` at a time. Returns the number of runs that failed. About 60 lines: one scheduling
/// loop whose state (running, next, stopping) is clearer in one place than split.
int run_pending(const Sweep& sweep, int jobs) {
  std::vector<std::size_t> pending;
  for (std::size_t i = 0; i < sweep.plan.runs.size(); ++i) {
    if (!read_sweep_outcome(sweep.run_dir(sweep.plan.runs[i]))) pending.push_back(i);
  }
  const std::size_t total = sweep.plan.runs.size();
  if (pending.empty()) {
    std::cout << "all " << plural(total, "run") << " of " << sweep.directory.string() << " are done"
              << std::endl;
    return 0;
  }
  std::cout << "running " << pending.size() << " of " << plural(total, "run") << ", " << jobs
            << " at a time; each run's output goes to "
            << (sweep.directory / "logs" / "<run>.log").string() << std::endl;
  std::filesystem::create_directories(sweep.directory / "logs");
  const std::filesystem::path executable = this_executable();
  const auto started_at = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return format_duration(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started_at).count());
  };
  InterruptHandlers interrupts;
  std::map<pid_t, std::size_t> running;
  std::size_t next = 0, finished = 0;
  int failures = 0;
  bool stopping = false;
  while ((!stopping && next < pending.size()) || !running.empty()) {
    while (!stopping && running.size() < static_cast<std::size_t>(jobs) && next < pending.size()) {
      const std::size_t index = pending[next++];
      const SweepRun& run = sweep.plan.runs[index];
      const pid_t pid = spawn_logged(
          {executable.string(), "sweep", sweep.directory.string(), "--run", std::to_string(index)},
          sweep.log_path(run));
      running[pid] = index;
      std::cout << "[" << elapsed() << "] started " << run.name << std::endl;
    }
    const std::optional<ChildExit> child = wait_for_child();
    if (!child) {
      if (interrupt_requested.load() && !stopping) {
        stopping = true;
        std::cout << "interrupted: stopping " << plural(running.size(), "run") << std::endl;
        for (const auto& [pid, index] : running) ::kill(pid, SIGTERM);
      }
      continue;
    }
    const auto found = running.find(child->pid);
    if (found == running.end()) continue;  // not one of ours
    const SweepRun& run = sweep.plan.runs[found->second];
    running.erase(found);
    ++finished;
    const std::string stamp = "[" + elapsed() + "]";
    const std::string progress =
        stamp + " " + std::to_string(finished) + "/" + std::to_string(pending.size());
    if (!report_exit(sweep, run, *child, stopping, stamp, progress)) ++failures;
  }
  if (stopping) {
    throw CommandError("interrupted; `upkie-rl sweep " + sweep.directory.string() +
                       "` continues the sweep (stopped runs resume from their last "
                       "checkpoint)");
  }
  return failures;
}

void print_plan(const Sweep& sweep) {
  const std::size_t total = sweep.plan.runs.size();
  std::cout << "sweep " << sweep.directory.string() << ": " << plural(total, "run") << " of "
            << sweep.base.env_id << " (";
  for (const SweepAxis& axis : sweep.plan.axes) {
    std::cout << plural(axis.values.size(), "value") << " of " << axis.key << " x ";
  }
  std::cout << plural(sweep.plan.seeds.size(), "seed") << ")" << std::endl;
  for (std::size_t i = 0; i < total; ++i) {
    std::cout << "  " << i << "  " << sweep.plan.runs[i].name << std::endl;
  }
  const std::string dir = sweep.directory.string();
  std::cout << "run them all here:             upkie-rl sweep " << dir << " [--jobs N]\n"
            << "or one per task of a launcher: upkie-rl sweep " << dir << " --run I   (I = 0.."
            << total - 1 << ")\n"
            << "then the summary:              upkie-rl sweep " << dir << " --summary" << std::endl;
}

/// Creates the sweep directory from --config, --seeds and --set.
Sweep create_sweep(const SweepOptions& options) {
  if (options.seeds.empty()) throw std::invalid_argument("sweep needs --seeds, e.g. --seeds 0:5");
  TrainingConfig base = load_training_config(options.config_path);
  std::vector<SweepAxis> axes;
  for (const std::string& text : options.axes) {
    SweepAxis axis = parse_sweep_axis(text);
    // One value is no axis: it changes the base configuration of every run.
    if (axis.values.size() == 1) {
      apply_overrides(base, {axis.key + "=" + axis.values.front()});
    } else {
      axes.push_back(std::move(axis));
    }
  }
  base.validate();
  const SweepPlan plan = make_sweep_plan(base, parse_seed_list(options.seeds), std::move(axes),
                                         options.evaluation_episodes);
  const std::filesystem::path directory =
      options.out.empty()
          ? std::filesystem::path("runs") /
                ("sweep-" + std::filesystem::path(options.config_path).stem().string() + "-" +
                 local_timestamp())
          : std::filesystem::path(options.out);
  write_sweep(directory, base, plan);
  return load_sweep(directory);
}

int default_jobs(const Sweep& sweep) {
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const int threads_per_run = static_cast<int>(std::max<std::int64_t>(1, sweep.base.env_threads));
  return std::max(1, cores / threads_per_run);
}

void run_sweep(const SweepOptions& options) {
  const bool creating = !options.config_path.empty();
  if (creating == !options.directory.empty()) {
    throw std::invalid_argument(
        "sweep takes either --config (with --seeds and --set) to start a sweep, or the "
        "directory of an existing one");
  }
  if (!creating && (!options.seeds.empty() || !options.axes.empty() || !options.out.empty())) {
    throw std::invalid_argument(
        "--seeds, --set and --output describe a new sweep: give them with --config");
  }
  if (creating && (options.run_index >= 0 || options.summary_only)) {
    throw std::invalid_argument("--run and --summary take the directory of an existing sweep");
  }
  const Sweep sweep = creating ? create_sweep(options) : load_sweep(options.directory);
  if (options.run_index >= 0) {
    if (static_cast<std::size_t>(options.run_index) >= sweep.plan.runs.size()) {
      throw std::invalid_argument("--run " + std::to_string(options.run_index) +
                                  ": the sweep has " + plural(sweep.plan.runs.size(), "run") +
                                  " (0 to " + std::to_string(sweep.plan.runs.size() - 1) + ")");
    }
    run_one(sweep, sweep.plan.runs[static_cast<std::size_t>(options.run_index)]);
    return;
  }
  if (options.plan_only || creating) print_plan(sweep);
  if (options.plan_only) return;
  int failures = 0;
  if (!options.summary_only) {
    failures = run_pending(sweep, options.jobs > 0 ? options.jobs : default_jobs(sweep));
  }
  std::cout << '\n' << write_sweep_summary(sweep) << '\n';
  std::cout << "summary: " << (sweep.directory / "summary.md").string() << ", "
            << (sweep.directory / "summary.csv").string()
            << "; return curves: " << (sweep.directory / "returns.png").string() << std::endl;
  if (failures > 0) {
    throw CommandError(plural(static_cast<std::size_t>(failures), "run") +
                       " failed (see their logs); `upkie-rl sweep " + sweep.directory.string() +
                       "` runs them again");
  }
}

}  // namespace

void add_sweep_command(CLI::App& app) {
  auto options = std::make_shared<SweepOptions>();
  CLI::App* command = app.add_subcommand(
      "sweep",
      "Independent trainings over seeds and settings, then a summary table and their return "
      "curves");
  command
      ->add_option("directory", options->directory,
                   "An existing sweep: run its unfinished runs (or one with --run, or only "
                   "the summary with --summary)")
      ->check(kNonEmptyPath);
  command->add_option("--config", options->config_path, "Base training configuration (YAML)")
      ->check(CLI::ExistingFile);
  command->add_option("--seeds", options->seeds,
                      "Seeds of each setting: A:B (A to B-1), A,B,C or A");
  command
      ->add_option("--set", options->axes,
                   "A key and the values to sweep, e.g. --set ppo.learning_rate_initial=1e-4,"
                   "3e-4 (repeatable: the grid of all combinations; one value sets the key "
                   "for every run)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  command
      ->add_option("--output", options->out,
                   "Directory of the new sweep (default: runs/sweep-<config>-<date>-<time>)")
      ->check(kNonEmptyPath);
  add_former_spelling(*command, "--out", "--output", options->out, kNonEmptyPath);
  command
      ->add_option("--jobs", options->jobs,
                   "Runs at once here (default: cores / env.threads, at least 1)")
      ->check(finite_range(1, 1024));
  command
      ->add_option("--eval-episodes", options->evaluation_episodes,
                   "Episodes of each run's final evaluation")
      ->check(finite_range(1, 100'000))
      ->capture_default_str();
  command->add_flag("--plan", options->plan_only,
                    "Write the sweep directory and list its runs and the commands that run "
                    "them, without training");
  command
      ->add_option("--run", options->run_index,
                   "Train and evaluate run I of the sweep only (for a launcher's tasks, "
                   "e.g. a Slurm job array)")
      ->check(finite_range(0, static_cast<double>(kMaxSweepRuns - 1)));
  command->add_flag("--summary", options->summary_only,
                    "Only write the summary of the runs finished so far");
  command->callback([options] { run_sweep(*options); });
}

}  // namespace upkie_rl::apps
