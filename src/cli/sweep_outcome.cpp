#include "cli/sweep_outcome.hpp"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "base/atomic_file.hpp"
#include "base/input_file.hpp"
#include "cli/command_error.hpp"

namespace upkie_rl::apps {

namespace {

constexpr const char* kFile = "evaluation.json";

/// JSON has no NaN: a missing value is null.
nlohmann::json number(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

double number_of(const nlohmann::json& value) {
  return value.is_null() ? std::numeric_limits<double>::quiet_NaN() : value.get<double>();
}

}  // namespace

// The keys of evaluation.json: the writer and the reader side by side.

void write_sweep_outcome(const std::filesystem::path& run_dir, const SweepOutcome& outcome) {
  const nlohmann::json json = {{"timesteps", outcome.timesteps},
                               {"train_seconds", number(outcome.train_seconds)},
                               {"training_mean_return", number(outcome.training_mean_return)},
                               {"model", outcome.model},
                               {"evaluation",
                                {{"episodes", outcome.evaluation.episodes},
                                 {"successes", outcome.evaluation.successes},
                                 {"mean_return", number(outcome.evaluation.mean_return)},
                                 {"std_return", number(outcome.evaluation.std_return)},
                                 {"mean_length", number(outcome.evaluation.mean_length)}}}};
  const std::filesystem::path path = run_dir / kFile;
  write_file_atomically<std::runtime_error>(path, json.dump(2) + '\n');
}

std::optional<SweepOutcome> read_sweep_outcome(const std::filesystem::path& run_dir) {
  const std::filesystem::path path = run_dir / kFile;
  std::error_code missing;
  if (!std::filesystem::exists(path, missing)) return std::nullopt;
  const std::string text =
      read_input_file<std::runtime_error>(path, "sweep outcome", kMaxSweepOutcomeBytes);
  try {
    const nlohmann::json json = nlohmann::json::parse(text);
    SweepOutcome outcome;
    outcome.timesteps = json.at("timesteps").get<std::int64_t>();
    outcome.train_seconds = number_of(json.at("train_seconds"));
    outcome.training_mean_return = number_of(json.at("training_mean_return"));
    outcome.model = json.at("model").get<std::string>();
    const nlohmann::json& evaluation = json.at("evaluation");
    outcome.evaluation.episodes = evaluation.at("episodes").get<int>();
    outcome.evaluation.successes = evaluation.at("successes").get<int>();
    outcome.evaluation.mean_return = number_of(evaluation.at("mean_return"));
    outcome.evaluation.std_return = number_of(evaluation.at("std_return"));
    outcome.evaluation.mean_length = number_of(evaluation.at("mean_length"));
    return outcome;
  } catch (const nlohmann::json::exception& error) {
    throw CommandError(path.string() + ": malformed (" + error.what() +
                       "); delete it to evaluate the run again");
  }
}

}  // namespace upkie_rl::apps
