#pragma once
/// @file
/// The controllers and policies that `upkie-rl evaluate` compares (contenders), and the
/// episodes of one contender in one set of conditions (a cell of a grid, a world of a
/// suite), run on a few threads. Shared by the grid (evaluate_command.cpp) and the suites
/// (suite_evaluation.cpp).

#include <cstdint>
#include <string>
#include <vector>

#include "cli/common_flags.hpp"
#include "envs/evaluation/episode_runner.hpp"
#include "envs/registry/env_factory.hpp"

namespace upkie_rl::apps {

/// One controller under evaluation.
struct Contender {
  std::string label;
  std::string model;   ///< Path, or empty for a built-in controller.
  std::string spec;    ///< Built-in controller, resolved (lqr designed).
  EnvOptions options;  ///< The environment's options for it, before the cell's.
};

/// How a contender's episodes are run.
struct EpisodePlan {
  int episodes = 10;
  std::uint64_t seed = 0;  ///< Episode e uses seed + e.
  int max_steps = kDefaultMaxSteps;
  /// Episode length [s] when positive, in place of max_steps: each cell's environment
  /// gets round(duration / its timestep) steps.
  double duration = 0.0;
  int threads = 1;  ///< Threads that run the cells; 0 or 1: the calling thread alone.
  /// Falls in the first `early_fall_time` seconds are counted apart [s]; 0: none.
  double early_fall_time = 0.0;
};

/// The episodes of one contender in one cell.
struct CellResult {
  int successes = 0;
  int early_falls = 0;  ///< Falls within EpisodePlan::early_fall_time.
  double mean_return = 0.0;
  double mean_length = 0.0;
  bool identical = false;  ///< Every episode had the same return and length.
  EpisodeSummary summary;  ///< All of it (tracking figures of velocity tasks).
};

/// The contenders of `models` and `controllers` ("[label=]path", "[label=]spec") on
/// `env_id`: models carry the task options they were trained with, then `base`; built-in
/// controllers are resolved on `env_id` (lqr designed, printed). Repeated labels get a
/// suffix.
/// @throws std::invalid_argument for a missing model or nothing to evaluate.
std::vector<Contender> make_contenders(const std::string& env_id,
                                       const std::vector<std::string>& models,
                                       const std::vector<std::string>& controllers,
                                       const EnvOptions& base);

/// Evaluates every (contender, cell) pair on the plan's threads, cell k of contender c in
/// the environments of factories[c][k]; returns results[c][k]. The first error stops the
/// others and is rethrown.
std::vector<std::vector<CellResult>> evaluate_all(
    const EpisodePlan& plan, const std::vector<Contender>& contenders,
    const std::vector<std::vector<EnvFactory>>& factories);

/// One warning on stderr when the episodes of some cell were all the same (their
/// environment starts every episode from the same state).
void warn_identical_cells(const EpisodePlan& plan,
                          const std::vector<std::vector<CellResult>>& results);

/// The episodes of every cell as one summary (tracking errors pooled over their steps).
EpisodeSummary pooled_summary(const std::vector<CellResult>& results);

}  // namespace upkie_rl::apps
