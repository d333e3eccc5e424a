#pragma once
/// @file
/// A sweep: independent training runs of one base configuration, over seeds and a grid of
/// overridden keys (`upkie-rl sweep`). The plan lives in a sweep directory, so that any
/// launcher (the local one, a Slurm job array, GNU parallel) can run its entries one at a
/// time with `upkie-rl sweep DIR --run I`:
///
///   sweep.yaml          the plan: evaluation settings, axes, seeds, and one entry per run
///   config.yaml         the base configuration, resolved (the sweep does not depend on the
///                       file it was made from)
///   runs/<name>/        each run's directory (the layout of `upkie-rl train`), with
///                       evaluation.json once its final model is evaluated
///   logs/<name>.log     what each run printed, when the local launcher ran it
///   summary.csv, summary.md, returns.png   written by the summary

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "rl/runs/training_config.hpp"

namespace upkie_rl {

/// Runs a sweep may hold (a plan of more is refused; `--run` takes 0 to this - 1).
inline constexpr std::size_t kMaxSweepRuns = 10'000;

/// One overridden key and the values the sweep gives it.
struct SweepAxis {
  std::string key;                  ///< A dotted config key, e.g. ppo.learning_rate_initial.
  std::vector<std::string> values;  ///< As written after `key=` on the command line.
};

/// One training of the sweep.
struct SweepRun {
  std::string name;  ///< Directory name, e.g. learning_rate_initial=1e-4_seed0.
  std::uint64_t seed = 0;
  std::vector<std::string> overrides;  ///< "key=value", one per axis, in axis order.
};

struct SweepPlan {
  int evaluation_episodes = 10;  ///< Episodes of the final evaluation of each run.
  /// Episode e of every final evaluation starts from seed evaluation_seed + e, so that runs
  /// are evaluated on the same episodes.
  std::uint64_t evaluation_seed = 1'000'000;
  /// An evaluation episode also ends after this many steps (the env's own limit applies).
  int evaluation_max_steps = 1000;
  std::vector<SweepAxis> axes;
  std::vector<std::uint64_t> seeds;
  std::vector<SweepRun> runs;  ///< Every combination of axis values, then every seed.
};

/// "A:B" (seeds A to B-1, as Python's range), "A,B,C", or "A". Throws
/// std::invalid_argument naming the text.
std::vector<std::uint64_t> parse_seed_list(const std::string& text);

/// "key=value1,value2,...". Commas inside brackets belong to the value
/// (policy.actor_hidden_sizes=[64,64],[128,128] has two values). Throws
/// std::invalid_argument naming the text.
SweepAxis parse_sweep_axis(const std::string& text);

/// Expands the grid: for each combination of axis values (the last axis varies fastest),
/// every seed. Checks that each run's configuration is valid (the base with the run's
/// overrides and seed), so that a bad value fails before any training starts. Throws
/// std::invalid_argument naming the run and the key.
SweepPlan make_sweep_plan(const TrainingConfig& base, std::vector<std::uint64_t> seeds,
                          std::vector<SweepAxis> axes, int evaluation_episodes);

/// The configuration of run `index`: the base, its overrides and its seed.
TrainingConfig sweep_run_config(const TrainingConfig& base, const SweepRun& run);

/// The overrides of a run as one label, e.g. "ppo.learning_rate_initial=1e-4" ("base"
/// without axes): runs with equal labels differ by their seed only.
std::string sweep_group_label(const SweepRun& run);

/// Writes `plan` as sweep.yaml and `base` as config.yaml into `directory` (created if
/// needed). Throws std::runtime_error if the directory already holds a different sweep.
void write_sweep(const std::filesystem::path& directory, const TrainingConfig& base,
                 const SweepPlan& plan);

/// A sweep directory, read back.
struct Sweep {
  std::filesystem::path directory;
  TrainingConfig base;
  SweepPlan plan;

  std::filesystem::path run_dir(const SweepRun& run) const { return directory / "runs" / run.name; }
  std::filesystem::path log_path(const SweepRun& run) const {
    return directory / "logs" / (run.name + ".log");
  }
};

/// Reads sweep.yaml and config.yaml of `directory`. Throws std::invalid_argument naming
/// the file and the key when they are missing or malformed.
Sweep load_sweep(const std::filesystem::path& directory);

}  // namespace upkie_rl
