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
#include "cli/common_flags.hpp"
#include "cli/contender_evaluation.hpp"
#include "cli/controller_option.hpp"
#include "cli/gnuplot_figure.hpp"
#include "cli/option_checks.hpp"
#include "cli/policy_controller.hpp"
#include "cli/robustness_grid.hpp"
#include "cli/suite_evaluation.hpp"
#include "cli/tracking_report.hpp"
#include "envs/controllers/builtin_controllers.hpp"
#include "envs/evaluation/episode_runner.hpp"
#include "envs/evaluation/evaluation_start.hpp"
#include "envs/registry/env_factory.hpp"
#include "model/robot_model.hpp"

namespace upkie_rl::apps {

namespace {

struct EvaluateOptions {
  std::string env_id;
  std::vector<std::string> models;       // [label=]path
  std::vector<std::string> controllers;  // [label=]spec
  std::string grid;
  std::string suite;  // a suite's name or file, instead of --env and --grid
  EpisodePlan plan;
  std::vector<std::string> env_options;
  bool json = false;
  bool exact_start = false;
  std::string output;
};

std::string percent(int successes, int episodes) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(0) << 100.0 * successes / episodes << '%';
  return out.str();
}

/// The grid of one contender: rows the first axis (or one row), columns the second.
void print_table(std::ostream& out, const Contender& contender, const std::vector<GridAxis>& axes,
                 const std::vector<CellResult>& results, int episodes,
                 const std::string& start_words) {
  out << contender.label << " (success rate over " << episodes << " episodes per cell "
      << start_words << ")\n";
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
                            const std::vector<std::vector<CellResult>>& results,
                            const std::vector<std::string>& start_words) {
  nlohmann::json summary = {{"env", options.env_id},
                            {"episodes_per_cell", options.plan.episodes},
                            {"seed", options.plan.seed},
                            {"max_steps", options.plan.max_steps}};
  summary["axes"] = nlohmann::json::array();
  for (const GridAxis& axis : axes)
    summary["axes"].push_back({{"name", axis.name}, {"values", axis.values}});
  summary["controllers"] = nlohmann::json::array();
  for (std::size_t c = 0; c < contenders.size(); ++c) {
    nlohmann::json entry = {{"label", contenders[c].label}, {"start", start_words[c]}};
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
          {"success_rate", static_cast<double>(cell.successes) / options.plan.episodes},
          {"mean_return", cell.mean_return},
          {"mean_length", cell.mean_length}};
      add_tracking_json(cell_json, cell.summary);
      entry["cells"].push_back(cell_json);
    }
    add_tracking_json(entry, pooled_summary(results[c]));
    entry["successes"] = successes;
    entry["success_rate"] =
        static_cast<double>(successes) / static_cast<double>(options.plan.episodes * cells.size());
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
    figure.x_label = x_axis ? axis_label(x_axis->name, env_id) : "";
    figure.y_label = y_axis ? axis_label(y_axis->name, env_id) : "";
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

/// `--suite`: the worlds of a suite file instead of a grid on one env.
/// Which of the plan's flags were given (they override a suite's own figures).
struct GivenFlags {
  bool episodes = false;
  bool seed = false;
  bool max_steps = false;
};

void run_suite_evaluation(const EvaluateOptions& options, const GivenFlags& given) {
  if (!options.env_id.empty() || !options.grid.empty()) {
    throw std::invalid_argument(
        "--suite names its environments and worlds: give it without "
        "--env and --grid");
  }
  if (!options.output.empty()) find_gnuplot();  // refuse at once, not after the work
  // The shipped suites are in the checkout the tool was built from (models/upkie/upkie.urdf
  // is three levels below its root).
  const std::filesystem::path source_dir =
      RobotModel::default_urdf_path().parent_path().parent_path().parent_path();
  const EvaluationSuite suite =
      read_evaluation_suite(find_suite_file(options.suite, source_dir), world_check());
  SuiteRequest request;
  request.models = options.models;
  request.controllers = options.controllers;
  request.base = parse_env_options(options.env_options);
  request.exact_start = options.exact_start;
  request.threads = options.plan.threads;
  if (given.episodes) request.episodes = options.plan.episodes;
  if (given.seed) request.seed = options.plan.seed;
  if (given.max_steps) request.max_steps = options.plan.max_steps;
  const SuiteResults run = run_suite(suite, request);
  std::cout << suite_table(run);
  if (!options.output.empty()) write_suite_outputs(options.output, run);
  if (options.json) std::cout << suite_json(run).dump() << std::endl;
}

void run_evaluate(const EvaluateOptions& options) {
  if (options.env_id.empty()) throw std::invalid_argument("--env is required (or --suite)");
  const std::vector<GridAxis> axes = parse_grid(options.grid);
  const EnvOptions base = parse_env_options(options.env_options);
  if (!options.output.empty()) find_gnuplot();  // refuse at once, not after the work
  const std::vector<Contender> contenders =
      make_contenders(options.env_id, options.models, options.controllers, base);
  const std::vector<std::vector<std::size_t>> cells = grid_cells(axes);
  // Every cell's options are checked, by making its factory, before any episode runs.
  std::vector<std::vector<EnvFactory>> factories(contenders.size());
  // Which start each contender's episodes had: random when any cell's were.
  std::vector<std::string> start_words(contenders.size());
  for (std::size_t c = 0; c < contenders.size(); ++c) {
    factories[c].reserve(cells.size());
    for (const auto& cell : cells) {
      EnvOptions all = contenders[c].options;
      const EnvOptions cell_env_options = cell_options(axes, cell);
      all.insert(all.end(), cell_env_options.begin(), cell_env_options.end());
      if (!options.exact_start) all = with_evaluation_start(options.env_id, all);
      factories[c].push_back(make_env_factory(options.env_id, all));
      const std::string words = evaluation_start_words(options.env_id, all, options.exact_start);
      if (start_words[c].empty() || words == "from random starts") start_words[c] = words;
    }
  }
  const auto results = evaluate_all(options.plan, contenders, factories);
  std::ostringstream table;
  for (std::size_t c = 0; c < contenders.size(); ++c) {
    print_table(table, contenders[c], axes, results[c], options.plan.episodes, start_words[c]);
  }
  std::cout << table.str();
  warn_identical_cells(options.plan, results);
  const nlohmann::json summary =
      summary_json(options, contenders, axes, cells, results, start_words);
  if (!options.output.empty()) {
    write_outputs(options.output, table.str(), summary, contenders, axes, results,
                  options.plan.episodes, options.env_id);
  }
  if (options.json) std::cout << summary.dump() << std::endl;
}

}  // namespace

void add_evaluate_command(CLI::App& app) {
  auto options = std::make_shared<EvaluateOptions>();
  CLI::App* command = app.add_subcommand(
      "evaluate",
      "Success rate and mean return of controllers and policies over a grid of perturbations");
  add_env_id_option(*command, options->env_id);
  command->add_option("--suite", options->suite,
                      "A suite of named worlds instead of --env and --grid: a file, or the name "
                      "of one in configs/suites/ (reality); docs/reality.md");
  command->add_option("--model", options->models,
                      "[label=]trained model (repeatable): deterministic policy, with the task "
                      "options it was trained with");
  command->add_option("--controller", options->controllers,
                      std::string("[label=]built-in controller (repeatable): ") + kControllerHelp);
  command->add_option("--grid", options->grid,
                      "Up to two axes name=start:stop:step or name=value, comma-separated: push "
                      "[N], mass, friction, lag [s], delay [steps], pitch [rad], or any "
                      "numeric environment option");
  CLI::Option* episodes = add_episodes_option(
      *command, options->plan.episodes, " per cell and controller (a suite's own unless given)");
  CLI::Option* seed =
      add_seed_option(*command, options->plan.seed,
                      "episode 0 of every cell (then seed + e; a suite's own unless given)");
  CLI::Option* max_steps =
      add_max_steps_option(*command, options->plan.max_steps,
                           "success: not terminated by then (a suite's own figure unless given)");
  add_env_option_option(*command, options->env_options, " for every cell");
  options->plan.threads = one_thread_per_core();
  add_threads_option(*command, options->plan.threads, "the cells (default: one per core)");
  add_json_flag(*command, options->json);
  command->add_flag("--exact-start", options->exact_start, kExactStartHelp);
  command
      ->add_option("--output", options->output,
                   "Directory for table.txt, summary.json and heatmap_<label>.png")
      ->check(kNonEmptyPath);
  command->callback([options, episodes, seed, max_steps] {
    if (options->suite.empty()) {
      run_evaluate(*options);
    } else {
      run_suite_evaluation(*options,
                           {episodes->count() > 0, seed->count() > 0, max_steps->count() > 0});
    }
  });
}

}  // namespace upkie_rl::apps
