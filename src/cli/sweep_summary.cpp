#include "cli/sweep_summary.hpp"

#include "cli/fixed_text.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "base/csv_field.hpp"
#include "cli/command_error.hpp"
#include "cli/gnuplot_figure.hpp"
#include "cli/progress_bar.hpp"
#include "cli/sweep_outcome.hpp"
#include "rl/logging/scalar_csv_writer.hpp"

namespace upkie_rl::apps {

namespace {

struct RunRow {
  const SweepRun* run = nullptr;
  std::optional<SweepOutcome> outcome;
  std::string status;  ///< "done", "trained N steps", "pending"
};

std::string run_status(const Sweep& sweep, const SweepRun& run,
                       const std::optional<SweepOutcome>& outcome) {
  if (outcome) return "done";
  const std::filesystem::path csv = sweep.run_dir(run) / "progress.csv";
  if (std::filesystem::exists(csv)) {
    try {
      const ScalarTable table = read_scalar_csv(csv);
      if (!table.rows.empty()) {
        const double steps = table.rows.back()[table.index("time/total_timesteps")];
        return "at " + with_thousands(static_cast<std::int64_t>(steps)) + " steps";
      }
    } catch (const std::exception&) {
      // A progress.csv still being written: the run has started.
    }
    return "started";
  }
  return "pending";
}

void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::trunc);
  out << text;
  if (!out.flush()) throw CommandError("cannot write " + path.string());
}

std::string runs_csv(const std::vector<RunRow>& rows) {
  std::ostringstream csv;
  csv << "run,seed,settings,status,timesteps,train_seconds,training_mean_return,"
         "evaluation_episodes,evaluation_mean_return,evaluation_std_return,"
         "evaluation_mean_length,evaluation_success_rate\n";
  for (const RunRow& row : rows) {
    csv << csv_field(row.run->name) << ',' << row.run->seed << ','
        << csv_field(sweep_group_label(*row.run)) << ',' << csv_field(row.status);
    if (row.outcome) {
      const SweepOutcome& o = *row.outcome;
      csv << ',' << o.timesteps << ',' << fixed_text(o.train_seconds, 2) << ','
          << fixed_text(o.training_mean_return, 3) << ',' << o.evaluation.episodes << ','
          << fixed_text(o.evaluation.mean_return, 3) << ','
          << fixed_text(o.evaluation.std_return, 3) << ','
          << fixed_text(o.evaluation.mean_length, 2) << ','
          << fixed_text(static_cast<double>(o.evaluation.successes) / o.evaluation.episodes, 4);
    } else {
      csv << ",,,,,,,,";
    }
    csv << '\n';
  }
  return csv.str();
}

/// Mean and spread over the seeds of each setting, in plan order.
std::string settings_table(const std::vector<RunRow>& rows) {
  std::vector<std::string> order;
  std::map<std::string, std::vector<const RunRow*>> groups;
  for (const RunRow& row : rows) {
    const std::string label = sweep_group_label(*row.run);
    if (groups.count(label) == 0) order.push_back(label);
    groups[label].push_back(&row);
  }
  std::ostringstream table;
  table << "| settings | runs done | evaluation return, mean ± std over seeds | min | max | "
           "episodes survived |\n|---|---|---|---|---|---|\n";
  for (const std::string& label : order) {
    std::vector<double> returns;
    int successes = 0, episodes = 0;
    for (const RunRow* row : groups[label]) {
      if (!row->outcome) continue;
      returns.push_back(row->outcome->evaluation.mean_return);
      successes += row->outcome->evaluation.successes;
      episodes += row->outcome->evaluation.episodes;
    }
    double mean = 0.0, spread = 0.0, low = NAN, high = NAN;
    for (double value : returns) {
      mean += value / static_cast<double>(returns.size());
      low = std::isnan(low) ? value : std::min(low, value);
      high = std::isnan(high) ? value : std::max(high, value);
    }
    for (double value : returns) {
      spread += (value - mean) * (value - mean) / static_cast<double>(returns.size());
    }
    table << "| " << label << " | " << returns.size() << " of " << groups[label].size() << " | "
          << (returns.empty() ? "-" : fixed_text(mean) + " ± " + fixed_text(std::sqrt(spread)))
          << " | " << fixed_text(low) << " | " << fixed_text(high) << " | "
          << (episodes > 0 ? fixed_text(100.0 * successes / episodes, 0) + " %" : "-") << " |\n";
  }
  return table.str();
}

std::string runs_table(const std::vector<RunRow>& rows) {
  std::ostringstream table;
  table << "| run | status | timesteps | training time | training return | evaluation return | "
           "evaluation length | survived |\n|---|---|---|---|---|---|---|---|\n";
  for (const RunRow& row : rows) {
    table << "| " << row.run->name << " | " << row.status << " | ";
    if (row.outcome) {
      const SweepOutcome& o = *row.outcome;
      table << with_thousands(o.timesteps) << " | " << format_duration(o.train_seconds) << " | "
            << fixed_text(o.training_mean_return) << " | " << fixed_text(o.evaluation.mean_return)
            << " ± " << fixed_text(o.evaluation.std_return) << " | "
            << fixed_text(o.evaluation.mean_length) << " | " << o.evaluation.successes << "/"
            << o.evaluation.episodes << " |\n";
    } else {
      table << "- | - | - | - | - | - |\n";
    }
  }
  return table.str();
}

CurvesFigure return_curves(const Sweep& sweep, const std::vector<RunRow>& rows) {
  CurvesFigure figure;
  figure.output = sweep.directory / "returns.png";
  figure.title = "Training return of each run (mean of the last 100 episodes)";
  figure.x_label = "environment steps";
  figure.y_label = "return (dimensionless)";
  for (const RunRow& row : rows) {
    const std::filesystem::path csv = sweep.run_dir(*row.run) / "progress.csv";
    if (!std::filesystem::exists(csv)) continue;
    ScalarTable table;
    try {
      table = read_scalar_csv(csv);
    } catch (const std::exception&) {
      continue;  // being written by a run in progress
    }
    CurvesFigure::Curve curve;
    curve.group = sweep_group_label(*row.run);
    const std::size_t steps = table.index("time/total_timesteps");
    const std::size_t returns = table.index("rollout/ep_rew_mean");
    for (const auto& values : table.rows) {
      curve.x.push_back(values[steps]);
      curve.y.push_back(values[returns]);
    }
    if (!curve.x.empty()) figure.curves.push_back(std::move(curve));
  }
  return figure;
}

}  // namespace

std::string write_sweep_summary(const Sweep& sweep) {
  std::vector<RunRow> rows;
  for (const SweepRun& run : sweep.plan.runs) {
    RunRow row;
    row.run = &run;
    row.outcome = read_sweep_outcome(sweep.run_dir(run));
    row.status = run_status(sweep, run, row.outcome);
    rows.push_back(std::move(row));
  }
  std::string markdown =
      "Final evaluation: deterministic policy, " + std::to_string(sweep.plan.evaluation_episodes) +
      " episodes per run (seeds from " + std::to_string(sweep.plan.evaluation_seed) + ", at most " +
      std::to_string(sweep.plan.evaluation_max_steps) + " steps each).\n\n" + settings_table(rows) +
      "\n" + runs_table(rows);
  write_file(sweep.directory / "summary.csv", runs_csv(rows));
  write_file(sweep.directory / "summary.md", markdown);
  draw_curves_figure(return_curves(sweep, rows));
  return markdown;
}

}  // namespace upkie_rl::apps
