/// @file
/// `upkie-rl plot RUN_DIR [RUN_DIR...]`: the seed's training figures from the runs'
/// progress.csv — loss.png, kl.png, return.png and length.png. One run: raw values
/// semi-transparent with their trailing mean; several: each run's trailing mean in its own
/// colour, named in the legend, over its raw values.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "apps/commands.hpp"
#include "cli/command_error.hpp"
#include "cli/gnuplot_figure.hpp"
#include "cli/option_checks.hpp"
#include "cli/smoothing_window.hpp"
#include "rl/logging/rolling_mean.hpp"
#include "rl/logging/scalar_csv_writer.hpp"

namespace upkie_rl::apps {

namespace {

struct PlotOptions {
  std::vector<std::string> run_dirs;
  int window = 50;
  bool window_given = false;  ///< --window given: say so when the run cannot take it
  std::string output_dir;
};

/// One figure of the training log: a column and how to name it.
struct LoggedQuantity {
  const char* file;
  const char* title;
  const char* column;
  const char* y_label;
};

constexpr LoggedQuantity kFigures[] = {
    {"loss.png", "Training loss", "train/loss", "loss (dimensionless)"},
    {"kl.png", "Approximate KL divergence", "train/approx_kl", "approx. KL [nat]"},
    {"return.png", "Mean episode return (last 100 episodes)", "rollout/ep_rew_mean",
     "return (dimensionless)"},
    {"length.png", "Mean episode length (last 100 episodes)", "rollout/ep_len_mean",
     "episode length [steps]"}};
constexpr const char* kStepColumn = "time/total_timesteps";
constexpr const char* kStepLabel = "environment steps";

/// A run's log.
struct RunLog {
  std::string name;  ///< The run directory's name, for the legend.
  ScalarTable table;

  std::vector<double> column(const std::string& name) const {
    const std::size_t index = table.index(name);
    std::vector<double> values;
    values.reserve(table.rows.size());
    for (const auto& row : table.rows) values.push_back(row[index]);
    return values;
  }
  bool has(const std::string& name) const {
    for (const std::string& column : table.columns) {
      if (column == name) return true;
    }
    return false;
  }
};

RunLog read_run(const std::string& run_dir) {
  const std::filesystem::path csv = std::filesystem::path(run_dir) / "progress.csv";
  if (!std::filesystem::exists(csv)) {
    throw CommandError("no progress.csv in " + run_dir +
                       " (is it a run directory of `upkie-rl train`?)");
  }
  RunLog run{std::filesystem::path(run_dir).lexically_normal().filename().string(),
             read_scalar_csv(csv)};
  if (run.name.empty()) run.name = std::filesystem::path(run_dir).parent_path().filename().string();
  if (run.table.rows.empty()) throw CommandError(csv.string() + ": no update logged yet");
  return run;
}

bool has_a_value(const std::vector<double>& values) {
  return std::any_of(values.begin(), values.end(), [](double value) { return !std::isnan(value); });
}

/// Draws the figures of one run. A quantity the log has no value of yet (an episode
/// return before any episode ended) is not drawn: gnuplot cannot draw an empty series,
/// and the former figure, if any, stays. Throws naming them after drawing the others.
void plot_one_run(const RunLog& run, std::size_t window, const std::filesystem::path& output) {
  std::vector<TrendFigure> figures;
  std::string undrawn;
  for (const LoggedQuantity& quantity : kFigures) {
    if (!run.has(quantity.column)) continue;  // older logs may lack a column
    if (!has_a_value(run.column(quantity.column))) {
      undrawn += (undrawn.empty() ? "" : ", ") + std::string(quantity.file);
      continue;
    }
    TrendFigure figure;
    figure.output = output / quantity.file;
    figure.title = quantity.title;
    figure.x_label = kStepLabel;
    figure.y_label = quantity.y_label;
    figure.x = run.column(kStepColumn);
    figure.raw = run.column(quantity.column);
    figure.smoothed = rolling_mean(figure.raw, window);
    figure.smoothed_label = smoothing_label(window);
    figures.push_back(std::move(figure));
  }
  if (!figures.empty()) draw_trend_figures(figures);
  for (const TrendFigure& figure : figures) {
    std::cout << "wrote " << figure.output.string() << std::endl;
  }
  if (!undrawn.empty()) {
    throw CommandError(undrawn + " not drawn: progress.csv of " + run.name +
                       " has no value of them in its " + std::to_string(run.table.rows.size()) +
                       " updates yet (no episode has ended); train longer, then plot again");
  }
}

void plot_runs(const std::vector<RunLog>& runs, std::size_t window,
               const std::filesystem::path& output) {
  for (const LoggedQuantity& quantity : kFigures) {
    CurvesFigure figure;
    figure.output = output / quantity.file;
    figure.title = std::string(quantity.title) + ", " + smoothing_label(window);
    figure.x_label = kStepLabel;
    figure.y_label = quantity.y_label;
    for (const RunLog& run : runs) {
      if (!run.has(quantity.column)) continue;
      const std::vector<double> raw = run.column(quantity.column);
      if (!has_a_value(raw)) continue;  // an empty curve; "no data yet" when all are
      figure.curves.push_back({run.name, run.column(kStepColumn), raw, true});
      figure.curves.push_back({run.name, run.column(kStepColumn), rolling_mean(raw, window)});
    }
    draw_curves_figure(figure);
    std::cout << "wrote " << figure.output.string() << std::endl;
  }
}

void run_plot(const PlotOptions& options) {
  std::vector<RunLog> runs;
  for (const std::string& run_dir : options.run_dirs) runs.push_back(read_run(run_dir));
  if (runs.size() > 1 && options.output_dir.empty()) {
    throw std::invalid_argument("several runs make one set of figures: give --output DIR");
  }
  const std::filesystem::path output(options.output_dir.empty() ? options.run_dirs.front()
                                                                : options.output_dir);
  std::filesystem::create_directories(output);
  // The window fits the shortest run (the figures name it), said when --window asked another.
  std::size_t updates = runs.front().table.rows.size();
  for (const RunLog& run : runs) updates = std::min(updates, run.table.rows.size());
  const auto asked = static_cast<std::size_t>(options.window);
  const std::size_t window = fitted_window(asked, updates);
  if (options.window_given && window != asked) {
    std::cout << "smoothing window: " << window << " updates (--window " << asked
              << " is more than a tenth of the " << updates << " updates logged)" << std::endl;
  }
  if (runs.size() == 1) {
    plot_one_run(runs.front(), window, output);
  } else {
    plot_runs(runs, window, output);
  }
}

}  // namespace

void add_plot_command(CLI::App& app) {
  auto options = std::make_shared<PlotOptions>();
  CLI::App* command = app.add_subcommand(
      "plot",
      "Draw loss.png, kl.png, return.png and length.png of training runs with gnuplot; "
      "several runs are overlaid, one colour each");
  command->add_option("run_dirs", options->run_dirs, "Run directories of `upkie-rl train`")
      ->required();
  CLI::Option* window =
      command
          ->add_option("--window", options->window,
                       "Trailing-mean window, in updates (at most a tenth of the run's updates)")
          ->check(finite_range(1, 1'000'000))
          ->capture_default_str();
  command
      ->add_option("--output", options->output_dir,
                   "Directory for the figures (default: the run directory; required for "
                   "several runs)")
      ->check(kNonEmptyPath);
  command->callback([options, window] {
    options->window_given = window->count() > 0;
    run_plot(*options);
  });
}

}  // namespace upkie_rl::apps
