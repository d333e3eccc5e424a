/// @file
/// `upkie-rl evaluate`: success rate and mean return of controllers and trained policies
/// over a grid of perturbations, as a table, a JSON summary and one heat map per
/// controller (docs/robustness.md).

#include <algorithm>
#include <atomic>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "apps/commands.hpp"
#include "apps/controller_option.hpp"
#include "apps/gnuplot_figure.hpp"
#include "apps/option_checks.hpp"
#include "apps/policy_controller.hpp"
#include "apps/robustness_grid.hpp"
#include "apps/tracking_report.hpp"
#include "envs/builtin_controllers.hpp"
#include "envs/episode_runner.hpp"
#include "envs/evaluation_start.hpp"
#include "envs/registry.hpp"

namespace upkie_rl::apps {

namespace {

struct EvaluateOptions {
  std::string env_id;
  std::vector<std::string> models;       // [label=]path
  std::vector<std::string> controllers;  // [label=]spec
  std::string grid;
  int episodes = 10;
  std::uint64_t seed = 0;
  int max_steps = 300;
  std::vector<std::string> env_options;
  int threads = 0;
  bool json = false;
  bool exact_start = false;
  std::string output;
};

/// One controller under evaluation.
struct Contender {
  std::string label;
  std::string model;   // path, or empty for a built-in controller
  std::string spec;    // built-in controller, resolved (lqr designed)
  EnvOptions options;  // the environment's options for it, before the cell's
};

struct CellResult {
  int successes = 0;
  double mean_return = 0.0;
  double mean_length = 0.0;
  bool identical = false;  ///< Every episode had the same return and length.
  EpisodeSummary summary;  ///< All of it (tracking figures of velocity tasks).
};

/// "label=value" splits at the first '=' when a label is given; else the label is derived.
std::pair<std::string, std::string> labelled(const std::string& item, bool is_model) {
  const std::size_t equal = item.find('=');
  if (equal != std::string::npos && equal > 0) {
    return {item.substr(0, equal), item.substr(equal + 1)};
  }
  return {is_model ? std::filesystem::path(item).stem().string() : item, item};
}

std::vector<Contender> make_contenders(const EvaluateOptions& options, const EnvOptions& base) {
  std::vector<Contender> contenders;
  for (const std::string& item : options.models) {
    auto [label, path] = labelled(item, true);
    if (!std::filesystem::exists(path)) throw std::invalid_argument("model " + path + " not found");
    contenders.push_back({label, path, "", options_for_model(path, options.env_id, base)});
  }
  for (const std::string& item : options.controllers) {
    auto [label, spec] = labelled(item, false);
    const std::string resolved =
        resolve_controller_spec(spec, design_env_factory(options.env_id, base));
    if (resolved != spec) std::cout << label << ": " << resolved << std::endl;
    contenders.push_back({label, "", resolved, base});
  }
  if (contenders.empty()) {
    throw std::invalid_argument("nothing to evaluate: give --model and/or --controller");
  }
  for (std::size_t i = 0; i < contenders.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (contenders[i].label == contenders[j].label)
        contenders[i].label += "_" + std::to_string(i);
    }
  }
  return contenders;
}

/// Runs the episodes of one cell: success = the episode was not terminated (it reached the
/// time limit or max_steps).
CellResult evaluate_cell(const EvaluateOptions& options, const Contender& contender,
                         const EnvFactory& make_cell_env) {
  std::unique_ptr<Env> env = make_cell_env();
  std::unique_ptr<Controller> controller = contender.model.empty()
                                               ? make_builtin_controller(contender.spec, *env)
                                               : make_policy_controller(contender.model, *env);
  std::vector<float> observation(env->observation_space().size());
  std::vector<float> action(env->action_space().size());
  std::vector<EpisodeOutcome> outcomes;
  for (int episode = 0; episode < options.episodes; ++episode) {
    outcomes.push_back(run_episode(*env, *controller,
                                   options.seed + static_cast<std::uint64_t>(episode),
                                   options.max_steps, observation, action));
  }
  const EpisodeSummary summary = summarize_episodes(outcomes);
  std::vector<double> returns;
  std::vector<int> lengths;
  for (const EpisodeOutcome& outcome : outcomes) {
    returns.push_back(outcome.total_reward);
    lengths.push_back(outcome.length);
  }
  CellResult result;
  result.identical = !identical_episodes_warning(returns, lengths).empty();
  result.successes = summary.successes;
  result.mean_return = summary.mean_return;
  result.mean_length = summary.mean_length;
  result.summary = summary;
  return result;
}

/// Evaluates every (contender, cell) pair on `threads` threads, cell k of contender c in the
/// environments of factories[c][k]; results[c][k].
std::vector<std::vector<CellResult>> evaluate_all(
    const EvaluateOptions& options, const std::vector<Contender>& contenders,
    const std::vector<std::vector<EnvFactory>>& factories) {
  const std::size_t num_cells = factories.front().size();
  std::vector<std::vector<CellResult>> results(contenders.size(),
                                               std::vector<CellResult>(num_cells));
  const std::size_t tasks = contenders.size() * num_cells;
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const auto work = [&] {
    for (std::size_t task = next++; task < tasks; task = next++) {
      const std::size_t c = task / num_cells;
      const std::size_t k = task % num_cells;
      try {
        results[c][k] = evaluate_cell(options, contenders[c], factories[c][k]);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next = tasks;  // the others stop after their current cell
      }
    }
  };
  const unsigned threads = options.threads > 0 ? static_cast<unsigned>(options.threads)
                                               : std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> workers;
  for (unsigned t = 1; t < std::min<std::size_t>(threads, tasks); ++t) workers.emplace_back(work);
  work();
  for (std::thread& worker : workers) worker.join();
  if (failure) std::rethrow_exception(failure);
  return results;
}

std::string percent(int successes, int episodes) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(0) << 100.0 * successes / episodes << '%';
  return out.str();
}

/// The episodes of every cell as one summary (tracking errors pooled over their steps).
EpisodeSummary pooled_summary(const std::vector<CellResult>& results) {
  EpisodeSummary pooled;
  int falls = 0;
  for (const CellResult& cell : results) {
    pooled.episodes += cell.summary.episodes;
    pooled.successes += cell.summary.successes;
    falls += cell.summary.episodes - cell.summary.successes;
    pooled.tracking += cell.summary.tracking;
  }
  pooled.has_tracking = pooled.tracking.active;
  pooled.fall_rate = pooled.episodes > 0 ? static_cast<double>(falls) / pooled.episodes : 0.0;
  return pooled;
}

/// The grid of one contender: rows the first axis (or one row), columns the second.
void print_table(std::ostream& out, const Contender& contender, const std::vector<GridAxis>& axes,
                 const std::vector<CellResult>& results, int episodes) {
  out << contender.label << " (success rate over " << episodes << " episodes per cell)\n";
  const std::size_t rows = axes.empty() ? 1 : axes[0].values.size();
  const std::size_t columns = axes.size() < 2 ? 1 : axes[1].values.size();
  constexpr int kWidth = 8;
  const std::string corner =
      axes.empty() ? "" : (axes.size() < 2 ? axes[0].name : axes[0].name + " \\ " + axes[1].name);
  out << std::setw(14) << std::left << corner << std::right;
  for (std::size_t c = 0; c < columns; ++c) {
    out << std::setw(kWidth)
        << (axes.size() < 2 ? std::string("") : format_value(axes[1].values[c]));
  }
  out << '\n';
  int total = 0;
  double mean_return = 0.0;
  for (std::size_t r = 0; r < rows; ++r) {
    out << std::setw(14) << std::left << (axes.empty() ? "all" : format_value(axes[0].values[r]))
        << std::right;
    for (std::size_t c = 0; c < columns; ++c) {
      const CellResult& cell = results[r * columns + c];
      out << std::setw(kWidth) << percent(cell.successes, episodes);
      total += cell.successes;
      mean_return += cell.mean_return / static_cast<double>(results.size());
    }
    out << '\n';
  }
  out << "overall " << percent(total, episodes * static_cast<int>(results.size())) << " (" << total
      << "/" << episodes * results.size() << " episodes), mean return " << std::fixed
      << std::setprecision(1) << mean_return << std::defaultfloat << "\n";
  const std::string tracking = tracking_text(pooled_summary(results));
  if (!tracking.empty()) out << tracking << '\n';
  out << '\n';
}

nlohmann::json summary_json(const EvaluateOptions& options,
                            const std::vector<Contender>& contenders,
                            const std::vector<GridAxis>& axes,
                            const std::vector<std::vector<std::size_t>>& cells,
                            const std::vector<std::vector<CellResult>>& results) {
  nlohmann::json summary = {{"env", options.env_id},
                            {"episodes_per_cell", options.episodes},
                            {"seed", options.seed},
                            {"max_steps", options.max_steps}};
  summary["axes"] = nlohmann::json::array();
  for (const GridAxis& axis : axes)
    summary["axes"].push_back({{"name", axis.name}, {"values", axis.values}});
  summary["controllers"] = nlohmann::json::array();
  for (std::size_t c = 0; c < contenders.size(); ++c) {
    nlohmann::json entry = {{"label", contenders[c].label}};
    if (contenders[c].model.empty()) {
      entry["controller"] = contenders[c].spec;
    } else {
      entry["model"] = contenders[c].model;
    }
    entry["cells"] = nlohmann::json::array();
    int successes = 0;
    for (std::size_t k = 0; k < cells.size(); ++k) {
      nlohmann::json values = nlohmann::json::object();
      for (std::size_t a = 0; a < axes.size(); ++a)
        values[axes[a].name] = axes[a].values[cells[k][a]];
      const CellResult& cell = results[c][k];
      successes += cell.successes;
      nlohmann::json cell_json = {
          {"values", values},
          {"successes", cell.successes},
          {"success_rate", static_cast<double>(cell.successes) / options.episodes},
          {"mean_return", cell.mean_return},
          {"mean_length", cell.mean_length}};
      add_tracking_json(cell_json, cell.summary);
      entry["cells"].push_back(cell_json);
    }
    add_tracking_json(entry, pooled_summary(results[c]));
    entry["successes"] = successes;
    entry["success_rate"] =
        static_cast<double>(successes) / static_cast<double>(options.episodes * cells.size());
    summary["controllers"].push_back(entry);
  }
  return summary;
}

std::string file_name(const std::string& label) {
  std::string name;
  for (const char c : label) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name;
}

void write_outputs(const std::filesystem::path& directory, const std::string& table,
                   const nlohmann::json& summary, const std::vector<Contender>& contenders,
                   const std::vector<GridAxis>& axes,
                   const std::vector<std::vector<CellResult>>& results, int episodes,
                   const std::string& env_id) {
  std::filesystem::create_directories(directory);
  std::ofstream(directory / "table.txt") << table;
  std::ofstream(directory / "summary.json") << summary.dump(2) << '\n';
  std::vector<HeatMapFigure> figures;
  for (std::size_t c = 0; c < contenders.size(); ++c) {
    HeatMapFigure figure;
    figure.output = directory / ("heatmap_" + file_name(contenders[c].label) + ".png");
    figure.title = contenders[c].label + " on " + env_id + ": success rate [%], " +
                   std::to_string(episodes) + " episodes per cell";
    // x: the last axis; y: the first of two.
    const GridAxis* x_axis = axes.empty() ? nullptr : &axes.back();
    const GridAxis* y_axis = axes.size() == 2 ? &axes.front() : nullptr;
    figure.x_label = x_axis ? x_axis->name : "";
    figure.y_label = y_axis ? y_axis->name : "";
    if (x_axis) {
      for (double value : x_axis->values) figure.x_values.push_back(format_value(value));
    } else {
      figure.x_values.emplace_back("nominal");
    }
    if (y_axis) {
      for (double value : y_axis->values) figure.y_values.push_back(format_value(value));
    } else {
      figure.y_values.emplace_back();
    }
    figure.values.reserve(results[c].size());
    for (const CellResult& cell : results[c]) {
      figure.values.push_back(100.0 * cell.successes / episodes);
    }
    figures.push_back(std::move(figure));
  }
  draw_heat_maps(figures);
  std::cout << "wrote " << (directory / "table.txt").string() << ", summary.json and "
            << figures.size() << " heat map(s) in " << directory.string() << std::endl;
}

/// One warning on stderr when the episodes of some cell were all the same.
void warn_identical_cells(const EvaluateOptions& options,
                          const std::vector<std::vector<CellResult>>& results) {
  if (options.episodes < 2) return;
  std::size_t identical = 0;
  std::size_t cells = 0;
  for (const auto& contender : results) {
    for (const CellResult& cell : contender) identical += cell.identical ? 1 : 0;
    cells += contender.size();
  }
  if (identical == 0) return;
  std::cerr << "upkie-rl: warning: in " << identical << " of " << cells << " cells, all "
            << options.episodes
            << " episodes were identical: their environment starts every episode from the same "
               "state (add an initial-state randomisation, or leave out --exact-start)"
            << std::endl;
}

void run_evaluate(const EvaluateOptions& options) {
  const std::vector<GridAxis> axes = parse_grid(options.grid);
  const EnvOptions base = parse_env_options(options.env_options);
  if (!options.output.empty()) find_gnuplot();  // refuse at once, not after the work
  const std::vector<Contender> contenders = make_contenders(options, base);
  const std::vector<std::vector<std::size_t>> cells = grid_cells(axes);
  // Every cell's options are checked, by making its factory, before any episode runs.
  std::vector<std::vector<EnvFactory>> factories(contenders.size());
  for (std::size_t c = 0; c < contenders.size(); ++c) {
    factories[c].reserve(cells.size());
    for (const auto& cell : cells) {
      EnvOptions all = contenders[c].options;
      const EnvOptions cell_env_options = cell_options(axes, cell);
      all.insert(all.end(), cell_env_options.begin(), cell_env_options.end());
      if (!options.exact_start) all = with_evaluation_start(options.env_id, all);
      factories[c].push_back(make_env_factory(options.env_id, all));
    }
  }
  const auto results = evaluate_all(options, contenders, factories);
  std::ostringstream table;
  for (std::size_t c = 0; c < contenders.size(); ++c) {
    print_table(table, contenders[c], axes, results[c], options.episodes);
  }
  std::cout << table.str();
  warn_identical_cells(options, results);
  const nlohmann::json summary = summary_json(options, contenders, axes, cells, results);
  if (!options.output.empty()) {
    write_outputs(options.output, table.str(), summary, contenders, axes, results, options.episodes,
                  options.env_id);
  }
  if (options.json) std::cout << summary.dump() << std::endl;
}

}  // namespace

void add_evaluate_command(CLI::App& app) {
  auto options = std::make_shared<EvaluateOptions>();
  CLI::App* command = app.add_subcommand(
      "evaluate",
      "Success rate and mean return of controllers and policies over a grid of perturbations");
  command->add_option("--env", options->env_id, "Environment id (see `upkie-rl envs`)")->required();
  command->add_option("--model", options->models,
                      "[label=]trained model (repeatable): deterministic policy, with the task "
                      "options it was trained with");
  command->add_option("--controller", options->controllers,
                      std::string("[label=]built-in controller (repeatable): ") + kControllerHelp);
  command->add_option("--grid", options->grid,
                      "Up to two axes name=start:stop:step or name=value, comma-separated: push "
                      "[N], mass, friction, lag [s], delay [steps], pitch [rad], or any "
                      "numeric environment option");
  command->add_option("--episodes", options->episodes, "Episodes per cell and controller")
      ->check(finite_range(1, kMaxEvaluationEpisodes))
      ->capture_default_str();
  command->add_option("--seed", options->seed, "Seed of episode 0 of every cell (then seed + e)")
      ->check(kSeed)
      ->capture_default_str();
  command
      ->add_option("--max-steps", options->max_steps,
                   "Success: not terminated within this many steps (or the env's time limit)")
      ->check(finite_range(1, 1'000'000'000))
      ->capture_default_str();
  command->add_option("--env-option", options->env_options,
                      "Environment option key=value for every cell (repeatable)");
  command->add_option("--threads", options->threads, "Worker threads (0: one per core)")
      ->check(finite_range(0, 1024))
      ->capture_default_str();
  command->add_flag("--json", options->json, "Print the summary as JSON on the last line");
  command->add_flag("--exact-start", options->exact_start, kExactStartHelp);
  command
      ->add_option("--output", options->output,
                   "Directory for table.txt, summary.json and heatmap_<label>.png")
      ->check(kNonEmptyPath);
  command->callback([options] { run_evaluate(*options); });
}

}  // namespace upkie_rl::apps
