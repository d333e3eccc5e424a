#include "cli/suite_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "base/csv_field.hpp"
#include "cli/fall_statistics.hpp"
#include "cli/fixed_text.hpp"
#include "cli/gnuplot_figure.hpp"
#include "cli/tracking_report.hpp"
#include "envs/evaluation/evaluation_start.hpp"
#include "envs/registry/env_factory.hpp"
#include "envs/registry/registry.hpp"

namespace upkie_rl::apps {
namespace {

/// "MuJoCo" of "Upkie-MuJoCo-Velocity": the engine, which tells a world's two rows apart.
std::string engine_of(const std::string& env_id) {
  const std::size_t first = env_id.find('-');
  const std::size_t second = env_id.find('-', first + 1);
  if (first == std::string::npos || second == std::string::npos) return env_id;
  return env_id.substr(first + 1, second - first - 1);
}

int falls(const CellResult& cell) { return cell.summary.episodes - cell.successes; }

/// The JSON and CSV name of a cell's fall_rate_upper_bound at kFallConfidence.
constexpr const char* kFallRateUpperKey = "fall_rate_upper_95";

/// The options of one world for one contender: its own, no time limit of the environment's
/// when the suite's episodes last `duration` seconds (a policy carries its training's
/// max_episode_steps, in its own steps), the suite's, the evaluation's (--env-option, which
/// may change the suite's: a policy trained with the body-height command on a standing
/// suite), the world's (which the evaluation's do not change), then the evaluation start (a
/// random initial state) unless exact_start.
EnvOptions world_options(const Contender& contender, const SuiteWorld& world, double duration,
                         const EnvOptions& evaluation_options, bool exact_start) {
  const auto world_own =
      world.options.begin() +
      static_cast<std::ptrdiff_t>(std::min(world.suite_option_count, world.options.size()));
  EnvOptions all = contender.options;
  if (duration > 0.0) all.emplace_back(kMaxEpisodeStepsOption, "0");
  all.insert(all.end(), world.options.begin(), world_own);
  all.insert(all.end(), evaluation_options.begin(), evaluation_options.end());
  all.insert(all.end(), world_own, world.options.end());
  return exact_start ? all : with_evaluation_start(world.env_id, all);
}

/// Runs the contenders of one env over the suite's worlds on it, into run.results.
void run_env(const std::string& env_id, const SuiteRequest& request, const EpisodePlan& plan,
             SuiteResults& run) {
  const std::vector<Contender> contenders =
      make_contenders(env_id, request.models, request.controllers, request.base);
  if (run.labels.empty()) {
    for (const Contender& contender : contenders) {
      run.labels.push_back(contender.label);
      run.descriptions.push_back(contender.model.empty() ? contender.spec : contender.model);
    }
  }
  std::vector<std::size_t> worlds;
  for (std::size_t w = 0; w < run.suite.worlds.size(); ++w) {
    if (run.suite.worlds[w].env_id == env_id) worlds.push_back(w);
  }
  std::vector<std::vector<EnvFactory>> factories(contenders.size());
  for (std::size_t c = 0; c < contenders.size(); ++c) {
    for (const std::size_t w : worlds) {
      const SuiteWorld& world = run.suite.worlds[w];
      const EnvOptions options =
          world_options(contenders[c], world, plan.duration, request.base, request.exact_start);
      factories[c].push_back(make_env_factory(env_id, options));
      const std::string words = evaluation_start_words(env_id, options, request.exact_start);
      if (run.start_words.empty() || words == "from random starts") run.start_words = words;
    }
  }
  const auto results = evaluate_all(plan, contenders, factories);
  warn_identical_cells(plan, results);
  for (std::size_t c = 0; c < contenders.size(); ++c) {
    for (std::size_t k = 0; k < worlds.size(); ++k) run.results[worlds[k]][c] = results[c][k];
  }
}

/// "10 s" or "500 steps": how long an episode of the suite may last.
std::string length_words(const EvaluationSuite& suite) {
  if (suite.duration > 0.0) {
    std::ostringstream words;
    words << suite.duration << " s";
    return words.str();
  }
  return std::to_string(suite.max_steps) + " steps";
}

/// "3/20 (2 early)" or "0/20".
std::string falls_text(const CellResult& cell) {
  std::string text = std::to_string(falls(cell)) + "/" + std::to_string(cell.summary.episodes);
  if (cell.early_falls > 0) text += " (" + std::to_string(cell.early_falls) + " early)";
  return text;
}

/// Totals of one contender over the worlds: falls, worlds with a fall, summed RMS.
struct ContenderTotals {
  int falls = 0;
  int early_falls = 0;
  int worlds_with_falls = 0;
  double rms_vx_sum = 0.0;  ///< Over the worlds where the contender had steps up.
};

ContenderTotals totals_of_contender(const SuiteResults& run, std::size_t c) {
  ContenderTotals totals;
  for (const auto& world : run.results) {
    totals.falls += falls(world[c]);
    totals.early_falls += world[c].early_falls;
    totals.worlds_with_falls += falls(world[c]) > 0 ? 1 : 0;
    const double rms = world[c].summary.tracking.rms_forward();
    if (std::isfinite(rms)) totals.rms_vx_sum += rms;
  }
  return totals;
}

/// Every contender's totals, in label order.
std::vector<ContenderTotals> totals_of(const SuiteResults& run) {
  std::vector<ContenderTotals> totals;
  for (std::size_t c = 0; c < run.labels.size(); ++c) totals.push_back(totals_of_contender(run, c));
  return totals;
}

/// "name (engine)" of world `w`.
std::string world_label(const SuiteResults& run, std::size_t w) {
  const SuiteWorld& world = run.suite.worlds[w];
  return world.name + " (" + engine_of(world.env_id) + ")";
}

/// The fall rate's upper bound of one cell (fall_statistics.hpp).
double upper_bound_of(const CellResult& cell) {
  return fall_rate_upper_bound(falls(cell), cell.summary.episodes);
}

/// Contender a against contender b: the worlds where a fell and b did not, and those where a
/// fell more often than chance allows (more_falls_p_value under 1 - kFallConfidence).
struct PairComparison {
  struct World {
    std::size_t index = 0;
    double p_value = 1.0;  ///< That a falls more often, one-sided.
  };
  std::vector<World> falls_where_other_stands;
  std::vector<World> falls_more_often;
};

PairComparison compare(const SuiteResults& run, std::size_t a, std::size_t b) {
  PairComparison comparison;
  for (std::size_t w = 0; w < run.results.size(); ++w) {
    const CellResult& cell_a = run.results[w][a];
    const CellResult& cell_b = run.results[w][b];
    if (falls(cell_a) == 0) continue;
    const PairComparison::World world{
        w, more_falls_p_value(falls(cell_a), cell_a.summary.episodes, falls(cell_b),
                              cell_b.summary.episodes)};
    if (falls(cell_b) == 0) comparison.falls_where_other_stands.push_back(world);
    if (world.p_value < 1.0 - kFallConfidence) comparison.falls_more_often.push_back(world);
  }
  return comparison;
}

/// One ordered pair of contenders (a against b) and its comparison.
struct OrderedComparison {
  std::size_t a = 0;
  std::size_t b = 0;
  PairComparison comparison;
};

/// Every ordered pair of distinct contenders, a-major: what the table and the JSON both say.
std::vector<OrderedComparison> ordered_comparisons(const SuiteResults& run) {
  std::vector<OrderedComparison> pairs;
  for (std::size_t a = 0; a < run.labels.size(); ++a) {
    for (std::size_t b = 0; b < run.labels.size(); ++b) {
      if (a != b) pairs.push_back({a, b, compare(run, a, b)});
    }
  }
  return pairs;
}

/// "0.500", or "< 0.001".
std::string p_text(double p_value) {
  return p_value < 0.001 ? std::string("< 0.001") : fixed_text(p_value, 3);
}

/// ": name (engine) 1/20 against 0/20, p 0.500, ..." (nothing for no world).
std::string worlds_text(const SuiteResults& run, std::size_t a, std::size_t b,
                        const std::vector<PairComparison::World>& worlds) {
  std::string text;
  for (const PairComparison::World& world : worlds) {
    text += (text.empty() ? ": " : ", ") + world_label(run, world.index) + " " +
            falls_text(run.results[world.index][a]) + " against " +
            falls_text(run.results[world.index][b]) + ", p " + p_text(world.p_value);
  }
  return text;
}

/// "from 20 episodes a world's falls bound its fall rate (one-sided 95 %): 0 -> 13.9 %, ...".
std::string fall_bounds_text(int episodes) {
  std::string text = "from " + std::to_string(episodes) +
                     " episodes a world's falls bound its fall rate (one-sided " +
                     fixed_text(100.0 * kFallConfidence, 0) + " % confidence):";
  for (int falls = 0; falls <= std::min(3, episodes); ++falls) {
    text += std::string(falls == 0 ? " " : ", ") + std::to_string(falls) + " -> " +
            fixed_text(100.0 * fall_rate_upper_bound(falls, episodes), 1) + " %";
  }
  return text;
}

void print_comparisons(std::ostream& out, const SuiteResults& run,
                       const std::vector<ContenderTotals>& totals) {
  const std::string test =
      "(one-sided Fisher exact test, p < " + fixed_text(1.0 - kFallConfidence, 2) + ")";
  for (const auto& [a, b, comparison] : ordered_comparisons(run)) {
    out << run.labels[a] << " falls where " << run.labels[b]
        << " stands: " << comparison.falls_where_other_stands.size() << " world(s)"
        << worlds_text(run, a, b, comparison.falls_where_other_stands) << '\n';
    out << run.labels[a] << " falls more often than " << run.labels[b] << ' ' << test << ": "
        << comparison.falls_more_often.size() << " world(s)"
        << worlds_text(run, a, b, comparison.falls_more_often) << '\n';
  }
  for (std::size_t a = 0; a < run.labels.size(); ++a) {
    for (std::size_t b = a + 1; b < run.labels.size(); ++b) {
      const double rms_a = totals[a].rms_vx_sum;
      const double rms_b = totals[b].rms_vx_sum;
      out << "forward tracking summed over the worlds: " << run.labels[a] << ' '
          << fixed_text(rms_a, 3) << " m/s, " << run.labels[b] << ' ' << fixed_text(rms_b, 3)
          << " m/s (" << run.labels[a] << " " << fixed_text(100.0 * (1.0 - rms_a / rms_b), 1)
          << " % lower)\n";
    }
  }
}

/// Every ordered pair of contenders' comparison, for the JSON: worlds as "name (engine)".
nlohmann::json comparisons_json(const SuiteResults& run) {
  nlohmann::json comparisons = nlohmann::json::array();
  const auto names = [&](const std::vector<PairComparison::World>& worlds) {
    nlohmann::json list = nlohmann::json::array();
    for (const PairComparison::World& world : worlds) {
      list.push_back({{"world", world_label(run, world.index)}, {"p_value", world.p_value}});
    }
    return list;
  };
  for (const auto& [a, b, comparison] : ordered_comparisons(run)) {
    comparisons.push_back({{"contender", run.labels[a]},
                           {"other", run.labels[b]},
                           {"falls_where_other_stands", names(comparison.falls_where_other_stands)},
                           {"falls_more_often", names(comparison.falls_more_often)}});
  }
  return comparisons;
}

}  // namespace

SuiteWorldCheck world_check() {
  return [](const SuiteWorld& world) { make_env_factory(world.env_id, world.options); };
}

SuiteResults run_suite(const EvaluationSuite& suite, const SuiteRequest& request) {
  SuiteResults run;
  run.suite = suite;
  if (request.episodes > 0) run.suite.episodes = request.episodes;
  if (request.max_steps > 0) {  // steps given: the same steps for every contender
    run.suite.max_steps = request.max_steps;
    run.suite.duration = 0.0;
  }
  if (request.seed) run.suite.seed = *request.seed;
  EpisodePlan plan;
  plan.episodes = run.suite.episodes;
  plan.seed = run.suite.seed;
  plan.max_steps = run.suite.max_steps;
  plan.duration = run.suite.duration;
  plan.threads = request.threads;
  plan.early_fall_time = run.suite.early_fall_time;
  run.results.assign(suite.worlds.size(),
                     std::vector<CellResult>(request.models.size() + request.controllers.size()));
  for (const std::string& env_id : suite.env_ids) run_env(env_id, request, plan, run);
  return run;
}

std::string suite_table(const SuiteResults& run) {
  std::ostringstream out;
  const EvaluationSuite& suite = run.suite;
  out << "suite " << suite.name << (suite.description.empty() ? "" : ": " + suite.description)
      << "\n"
      << suite.episodes << " episodes per world and controller, at most " << length_words(suite)
      << ", seeds " << suite.seed << ".. " << run.start_words << "; falls (early: within "
      << suite.early_fall_time << " s), forward and yaw tracking RMS [m/s, rad/s], mean return\n";
  out << std::left << std::setw(34) << "world" << std::setw(8) << "engine";
  for (const std::string& label : run.labels) out << " | " << std::setw(36) << label;
  out << '\n';
  for (std::size_t w = 0; w < run.results.size(); ++w) {
    const SuiteWorld& world = suite.worlds[w];
    out << std::setw(34) << world.name << std::setw(8) << engine_of(world.env_id);
    for (const CellResult& cell : run.results[w]) {
      std::ostringstream entry;
      entry << std::setw(14) << falls_text(cell) << ' ' << std::setw(6)
            << fixed_text(cell.summary.tracking.rms_forward(), 3) << ' ' << std::setw(6)
            << fixed_text(cell.summary.tracking.rms_yaw(), 3) << ' '
            << fixed_text(cell.mean_return, 1);
      out << " | " << std::setw(36) << entry.str();
    }
    out << '\n';
  }
  out << std::right << '\n';
  const std::vector<ContenderTotals> totals = totals_of(run);
  for (std::size_t c = 0; c < run.labels.size(); ++c) {
    out << run.labels[c] << ": " << totals[c].falls << " falls (" << totals[c].early_falls
        << " early) in " << totals[c].worlds_with_falls << " of " << run.results.size()
        << " worlds; forward tracking RMS summed over the worlds "
        << fixed_text(totals[c].rms_vx_sum, 3) << " m/s\n";
  }
  out << fall_bounds_text(suite.episodes) << '\n';
  print_comparisons(out, run, totals);
  return out.str();
}

nlohmann::json suite_json(const SuiteResults& run) {
  const EvaluationSuite& suite = run.suite;
  nlohmann::json json = {
      {"suite", suite.name},
      {"description", suite.description},
      {"episodes", suite.episodes},
      {"seed", suite.seed},
      {"max_steps",
       suite.duration > 0.0 ? nlohmann::json(nullptr) : nlohmann::json(suite.max_steps)},
      {"duration", suite.duration > 0.0 ? nlohmann::json(suite.duration) : nlohmann::json(nullptr)},
      {"early_fall_time", suite.early_fall_time},
      {"start", run.start_words},
      {"contenders", nlohmann::json::array()},
      {"worlds", nlohmann::json::array()}};
  const std::vector<ContenderTotals> all_totals = totals_of(run);
  for (std::size_t c = 0; c < run.labels.size(); ++c) {
    const ContenderTotals& totals = all_totals[c];
    json["contenders"].push_back({{"label", run.labels[c]},
                                  {"source", run.descriptions[c]},
                                  {"falls", totals.falls},
                                  {"early_falls", totals.early_falls},
                                  {"worlds_with_falls", totals.worlds_with_falls},
                                  {"tracking_rms_vx_sum", totals.rms_vx_sum}});
  }
  for (std::size_t w = 0; w < run.results.size(); ++w) {
    const SuiteWorld& world = suite.worlds[w];
    nlohmann::json options = nlohmann::json::object();
    for (const auto& [name, value] : world.options) options[name] = value;
    nlohmann::json results = nlohmann::json::object();
    for (std::size_t c = 0; c < run.labels.size(); ++c) {
      const CellResult& cell = run.results[w][c];
      nlohmann::json entry = {
          {"episodes", cell.summary.episodes}, {"falls", falls(cell)},
          {"early_falls", cell.early_falls},   {"mean_return", cell.mean_return},
          {"mean_length", cell.mean_length},   {kFallRateUpperKey, upper_bound_of(cell)}};
      add_tracking_json(entry, cell.summary);
      results[run.labels[c]] = entry;
    }
    json["worlds"].push_back(
        {{"name", world.name}, {"env", world.env_id}, {"options", options}, {"results", results}});
  }
  json["comparisons"] = comparisons_json(run);
  return json;
}

std::string suite_csv(const SuiteResults& run) {
  std::ostringstream out;
  out << "world,env,contender,episodes,falls,early_falls,tracking_rms_vx,tracking_rms_wz,"
         "mean_return,"
      << kFallRateUpperKey << '\n';
  out << std::setprecision(9);
  for (std::size_t w = 0; w < run.results.size(); ++w) {
    const SuiteWorld& world = run.suite.worlds[w];
    for (std::size_t c = 0; c < run.labels.size(); ++c) {
      const CellResult& cell = run.results[w][c];
      out << csv_field(world.name) << ',' << world.env_id << ',' << csv_field(run.labels[c]) << ','
          << cell.summary.episodes << ',' << falls(cell) << ',' << cell.early_falls << ','
          << cell.summary.tracking.rms_forward() << ',' << cell.summary.tracking.rms_yaw() << ','
          << cell.mean_return << ',' << upper_bound_of(cell) << '\n';
    }
  }
  return out.str();
}

void write_suite_outputs(const std::filesystem::path& directory, const SuiteResults& run) {
  std::filesystem::create_directories(directory);
  std::ofstream(directory / "table.txt") << suite_table(run);
  std::ofstream(directory / "summary.json") << suite_json(run).dump(2) << '\n';
  std::ofstream(directory / "results.csv") << suite_csv(run);
  HeatMapFigure figure;
  figure.output = directory / "falls.png";
  // Episodes without a fall, on the success-rate scale of every heat map (green: none fell).
  figure.title = "suite " + run.suite.name + ": episodes without a fall [% of " +
                 std::to_string(run.suite.episodes) + "]";
  figure.x_label = "controller";
  figure.x_values = run.labels;
  figure.y_label = "world";
  for (std::size_t w = 0; w < run.results.size(); ++w) {
    const SuiteWorld& world = run.suite.worlds[w];
    figure.y_values.push_back(world.name + " (" + engine_of(world.env_id) + ")");
    for (const CellResult& cell : run.results[w]) {
      figure.values.push_back(100.0 * cell.successes / std::max(1, cell.summary.episodes));
    }
  }
  draw_heat_maps({figure});
  std::cout << "wrote table.txt, summary.json, results.csv and falls.png in " << directory.string()
            << std::endl;
}

}  // namespace upkie_rl::apps
