#pragma once
/// @file
/// What one run of a sweep produced: its training and the final evaluation of its model,
/// saved as evaluation.json in the run's directory (the mark of a finished run).

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "envs/evaluation/episode_runner.hpp"

namespace upkie_rl::apps {

struct SweepOutcome {
  std::int64_t timesteps = 0;         ///< Trained timesteps.
  double train_seconds = 0.0;         ///< Of the last process that trained it (resumed: the rest).
  double training_mean_return = 0.0;  ///< Raw, last 100 training episodes (NaN: none).
  std::string model;                  ///< Final model, relative to the run directory.
  EpisodeSummary evaluation;          ///< Deterministic policy on the plan's evaluation episodes.
};

/// Writes `outcome` as JSON to run_dir/evaluation.json (through a temporary file).
void write_sweep_outcome(const std::filesystem::path& run_dir, const SweepOutcome& outcome);

/// Largest evaluation.json read: ours take about 300 bytes.
inline constexpr std::uintmax_t kMaxSweepOutcomeBytes = std::uintmax_t{1} << 20;

/// Reads run_dir/evaluation.json; nothing when the run has not finished (no such file). Throws
/// std::runtime_error naming the file when it is malformed.
std::optional<SweepOutcome> read_sweep_outcome(const std::filesystem::path& run_dir);

}  // namespace upkie_rl::apps
