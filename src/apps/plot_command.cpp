/// @file
/// `upkie-rl plot RUN_DIR`: the seed's training figures from a run's progress.csv —
/// loss.png, kl.png and return.png, raw values semi-transparent with a rolling mean.

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "apps/commands.hpp"
#include "apps/gnuplot_figure.hpp"
#include "rl/rolling_mean.hpp"
#include "rl/scalar_csv_writer.hpp"

namespace upkie_rl::apps {

namespace {

struct PlotOptions {
  std::string run_dir;
  int window = 50;
  std::string output_dir;
};

void run_plot(const PlotOptions& options) {
  const std::filesystem::path csv = std::filesystem::path(options.run_dir) / "progress.csv";
  if (!std::filesystem::exists(csv)) {
    throw std::runtime_error("no progress.csv in " + options.run_dir +
                             " (is it a run directory of `upkie-rl train`?)");
  }
  const ScalarTable table = read_scalar_csv(csv);
  if (table.rows.empty()) throw std::runtime_error(csv.string() + ": no update logged yet");
  const std::filesystem::path output =
      std::filesystem::path(options.output_dir.empty() ? options.run_dir : options.output_dir);
  std::filesystem::create_directories(output);

  const std::size_t step = table.index("time/total_timesteps");
  auto column = [&](const std::string& name) {
    const std::size_t index = table.index(name);
    std::vector<double> values;
    for (const auto& row : table.rows) values.push_back(row[index]);
    return values;
  };
  std::vector<double> x;
  for (const auto& row : table.rows) x.push_back(row[step]);
  const auto window = static_cast<std::size_t>(options.window);
  const std::string smoothed_label = "rolling mean (window " + std::to_string(window) + ")";
  auto figure = [&](const std::string& file, const std::string& title, const std::string& tag,
                    const std::string& y_label) {
    TrendFigure out;
    out.output = output / file;
    out.title = title;
    out.x_label = "timesteps";
    out.y_label = y_label;
    out.x = x;
    out.raw = column(tag);
    out.smoothed = rolling_mean(out.raw, window);
    out.smoothed_label = smoothed_label;
    return out;
  };
  const std::vector<TrendFigure> figures{
      figure("loss.png", "Training loss", "train/loss", "loss"),
      figure("kl.png", "Approximate KL divergence", "train/approx_kl", "approx. KL"),
      figure("return.png", "Mean episode return (last 100 episodes)", "rollout/ep_rew_mean",
             "return")};
  draw_trend_figures(figures);
  for (const TrendFigure& f : figures) std::cout << "wrote " << f.output.string() << std::endl;
}

}  // namespace

void add_plot_command(CLI::App& app) {
  auto options = std::make_shared<PlotOptions>();
  CLI::App* command = app.add_subcommand(
      "plot", "Draw loss.png, kl.png and return.png of a training run with gnuplot");
  command->add_option("run_dir", options->run_dir, "Run directory of `upkie-rl train`")->required();
  command->add_option("--window", options->window, "Rolling-mean window, in updates")
      ->check(CLI::Range(1, 1'000'000))
      ->capture_default_str();
  command->add_option("--output", options->output_dir,
                      "Directory for the figures (default: the run directory)");
  command->callback([options] { run_plot(*options); });
}

}  // namespace upkie_rl::apps
