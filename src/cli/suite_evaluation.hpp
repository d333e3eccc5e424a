#pragma once
/// @file
/// `upkie-rl evaluate --suite`: policies and controllers over the named worlds of an
/// EvaluationSuite (envs/evaluation/evaluation_suite.hpp), side by side: falls (early ones apart),
/// tracking RMS and return per world, as a table, JSON, CSV and a heat map of falls.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/contender_evaluation.hpp"
#include "envs/evaluation/evaluation_suite.hpp"

namespace upkie_rl::apps {

/// What `evaluate --suite` was asked.
struct SuiteRequest {
  std::vector<std::string> models;       ///< [label=]path
  std::vector<std::string> controllers;  ///< [label=]spec
  EnvOptions base;                       ///< --env-option: after the suite's, before a world's
  bool exact_start = false;              ///< Keep the environments' own initial states.
  int threads = 1;                       ///< Threads; 0 or 1: the calling thread alone.
  /// Overrides of the suite's figures when positive (a quick run of a shipped suite).
  int episodes = 0;
  int max_steps = 0;
  std::optional<std::uint64_t> seed;
};

/// A suite's results: results[w][c] for world w of suite.worlds and contender c.
struct SuiteResults {
  EvaluationSuite suite;
  std::vector<std::string> labels;        ///< Contender labels, the same on every env.
  std::vector<std::string> descriptions;  ///< Model path or resolved controller, by label.
  std::vector<std::vector<CellResult>> results;
  std::string start_words;  ///< Which start the episodes had: random when any world's were.
};

/// The checks a suite's worlds get when it is read: each world's environment is made.
SuiteWorldCheck world_check();

/// Runs every contender in every world (each env's contenders made on that env: a model
/// with its task options, lqr designed there).
/// @throws std::invalid_argument as make_contenders and the environments' options.
SuiteResults run_suite(const EvaluationSuite& suite, const SuiteRequest& request);

/// The table printed and written: one row per world and env, for each contender falls of
/// episodes (early falls), RMS of forward velocity and yaw rate, mean return; then each
/// contender's totals, what a count of falls bounds (fall_statistics.hpp), and each
/// contender beside each other: the worlds where it falls and the other stands, those where
/// it falls more often beyond chance (one-sided Fisher exact test), each with its p-value,
/// and the summed forward tracking.
std::string suite_table(const SuiteResults& run);

/// The same as JSON (suite, worlds with options and results per label, each result's
/// fall_rate_upper_95, totals, and `comparisons`: for each ordered pair of contenders the
/// worlds, with p-values, where the first falls and the other stands and where it falls
/// more often).
nlohmann::json suite_json(const SuiteResults& run);

/// One CSV row per world, env and contender (its fall_rate_upper_95 last).
std::string suite_csv(const SuiteResults& run);

/// Writes table.txt, summary.json, results.csv and falls.png (worlds x contenders, the
/// share of episodes without a fall [%], green for none) in `directory`.
void write_suite_outputs(const std::filesystem::path& directory, const SuiteResults& run);

}  // namespace upkie_rl::apps
