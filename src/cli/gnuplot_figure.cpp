#include "cli/gnuplot_figure.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "cli/command_error.hpp"

namespace upkie_rl::apps {

namespace {

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

/// A tic label: gnuplot reads tic labels as formats, so a '%' ("payload 30 %") is doubled.
std::string tic_label(const std::string& text) {
  std::string escaped;
  for (char c : text) escaped += c == '%' ? std::string("%%") : std::string(1, c);
  const std::string& label = escaped;  // const: std::quoted's overload would be chosen
  return quoted(label);
}

bool probe_cairo(const std::string& gnuplot) {
  const std::string command = gnuplot + " -e 'set terminal' 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return false;
  std::string output;
  std::array<char, 4096> buffer{};
  std::size_t read = 0;
  while ((read = fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    output.append(buffer.data(), read);
  pclose(pipe);
  return output.find("pngcairo") != std::string::npos;
}

/// Whether `gnuplot` has the pngcairo terminal (asked once per process).
bool has_cairo(const std::string& gnuplot) {
  static const bool cairo = probe_cairo(gnuplot);
  return cairo;
}

/// The terminal of a figure of width x height pixels written to `output`: SVG for a .svg
/// file, else PNG by pngcairo, or png without cairo. Text is never "enhanced": titles are
/// file and run names and legends, where gnuplot would read '_' as a subscript and '~' as
/// an overprint (it drew "(lags ~25)" with the 5 over the 2).
std::string terminal_line(const std::string& gnuplot, const std::filesystem::path& output,
                          int width, int height) {
  const std::string size = " size " + std::to_string(width) + "," + std::to_string(height);
  std::string terminal;
  if (output.extension() == ".svg") {
    terminal = "set terminal svg" + size + " font 'sans,11'";
  } else if (has_cairo(gnuplot)) {
    terminal = "set terminal pngcairo" + size + " font 'sans,11'";
  } else {
    terminal = "set terminal png truecolor" + size;
  }
  return terminal + "\nset termoption noenhanced\n";
}

/// The last line gnuplot printed that says what went wrong (its errors end with the
/// reason, e.g. "line 12: x range is invalid"), or empty.
std::string gnuplot_reason(const std::string& log_path) {
  FILE* log = std::fopen(log_path.c_str(), "r");
  if (log == nullptr) return {};
  std::string reason;
  std::array<char, 512> line{};
  while (std::fgets(line.data(), line.size(), log) != nullptr) {
    std::string text(line.data());
    const std::size_t start = text.find_first_not_of(" \t");
    const std::size_t end = text.find_last_not_of(" \t\r\n");
    if (start != std::string::npos && end != std::string::npos && text.find("line ") == start) {
      reason = text.substr(start, end - start + 1);
    }
  }
  std::fclose(log);
  return reason;
}

/// Figures drawn aside (`<figure>.tmp.<pid>`) and renamed over their files only once gnuplot
/// succeeded: a failed drawing leaves no empty PNG and the former figures as they were.
class FiguresAside {
 public:
  FiguresAside() = default;
  FiguresAside(const FiguresAside&) = delete;
  FiguresAside& operator=(const FiguresAside&) = delete;
  ~FiguresAside() {
    std::error_code error;
    for (const auto& [aside, output] : figures_) std::filesystem::remove(aside, error);
  }
  /// The file gnuplot writes for `output`.
  std::string add(const std::filesystem::path& output) {
    std::filesystem::path aside = output;
    aside += ".tmp." + std::to_string(::getpid());
    figures_.emplace_back(aside, output);
    return aside.string();
  }
  /// The names of the figures, for messages.
  std::string names() const {
    std::string names;
    for (const auto& [aside, output] : figures_) {
      names += (names.empty() ? "" : ", ") + output.filename().string();
    }
    return names;
  }
  void commit() {
    for (const auto& [aside, output] : figures_) std::filesystem::rename(aside, output);
    figures_.clear();
  }

 private:
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> figures_;
};

/// Runs `text` through gnuplot, its output to a log aside, and renames the figures over
/// their files when it succeeded; else throws naming the figures and gnuplot's reason.
void run_gnuplot(const std::string& gnuplot, const std::string& text, FiguresAside& figures) {
  const std::string log_path =
      (std::filesystem::temp_directory_path() / ("upkie_rl_gnuplot." + std::to_string(::getpid())))
          .string();
  const std::string command = gnuplot + " >'" + log_path + "' 2>&1";
  FILE* pipe = popen(command.c_str(), "w");
  if (pipe == nullptr) throw CommandError("cannot start " + gnuplot);
  const std::size_t written = fwrite(text.data(), 1, text.size(), pipe);
  const int status = pclose(pipe);
  const std::string reason = gnuplot_reason(log_path);
  std::error_code error;
  std::filesystem::remove(log_path, error);
  if (written != text.size() || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw CommandError("gnuplot failed to draw " + figures.names() + " (exit status " +
                       std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")" +
                       (reason.empty() ? std::string() : ": " + reason));
  }
  figures.commit();
}

/// Axis settings shared by the line figures: the x axis ends at the first and last data, and
/// the key sits above the plot area in one row, where it cannot hide a curve (inside, at a
/// corner, it covered the ends of the curves: a velocity figure's last seconds, a rising
/// return).
constexpr const char* kLineAxes =
    "set autoscale xfix\nset key outside top center horizontal reverse Left samplen 2 width 2\n";

}  // namespace

std::string flat_series_range(const std::vector<std::vector<double>>& series) {
  double low = INFINITY;
  double high = -INFINITY;
  for (const auto& values : series) {
    for (double value : values) {
      if (std::isnan(value)) continue;
      low = std::min(low, value);
      high = std::max(high, value);
    }
  }
  if (!std::isfinite(low) || !std::isfinite(high)) return {};
  const double magnitude = std::max(std::abs(low), std::abs(high));
  if (high - low > 1e-6 * magnitude && high > low) return {};
  const double middle = 0.5 * (low + high);
  const double half = magnitude > 0.0 ? 0.1 * magnitude : 1.0;
  std::ostringstream range;
  range << std::setprecision(17) << '[' << middle - half << ':' << middle + half << ']';
  return range.str();
}

std::string find_gnuplot() {
  const char* path = std::getenv("PATH");
  std::stringstream directories(path != nullptr ? path : "/usr/bin:/bin");
  for (std::string directory; std::getline(directories, directory, ':');) {
    if (directory.empty()) continue;
    std::string candidate = directory + "/gnuplot";
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  throw CommandError(
      "gnuplot not found on PATH: install it (Debian: apt-get install gnuplot-nox, or run "
      "scripts/install-deps.sh)");
}

void draw_trend_figures(const std::vector<TrendFigure>& figures) {
  const std::string gnuplot = find_gnuplot();
  FiguresAside aside;
  std::ostringstream script;
  script << "set grid\nset datafile missing 'NaN'\nset format x '%.1s%c'\n" << kLineAxes;
  for (std::size_t f = 0; f < figures.size(); ++f) {
    const TrendFigure& figure = figures[f];
    script << terminal_line(gnuplot, figure.output, 900, 540);
    const std::string block = "$data" + std::to_string(f);
    script << block << " << EOD\n";
    for (std::size_t i = 0; i < figure.x.size(); ++i) {
      if (std::isnan(figure.raw[i])) continue;
      script << figure.x[i] << ' ' << figure.raw[i] << ' ' << figure.smoothed[i] << '\n';
    }
    script << "EOD\n";
    script << "set output " << quoted(aside.add(figure.output)) << '\n';
    script << "set title " << quoted(figure.title) << '\n';
    script << "set xlabel " << quoted(figure.x_label) << '\n';
    script << "set ylabel " << quoted(figure.y_label) << '\n';
    const std::string y_range = flat_series_range({figure.raw, figure.smoothed});
    script << (y_range.empty() ? "set autoscale y\n" : "set yrange " + y_range + "\n");
    // Colours are #AARRGGBB: alpha 0x99 draws the raw values semi-transparent.
    script << "plot " << block << " using 1:2 with lines lc rgb '#991f77b4' lw 1 title 'raw', "
           << block << " using 1:3 with lines lc rgb '#d62728' lw 2.5 title "
           << quoted(figure.smoothed_label) << '\n';
    script << "unset output\n";
  }
  run_gnuplot(gnuplot, script.str(), aside);
}

void draw_curves_figure(const CurvesFigure& figure) {
  const std::string gnuplot = find_gnuplot();
  FiguresAside aside;
  // A qualitative palette (matplotlib's tab10), repeated past ten groups.
  static constexpr std::array<const char*, 10> kColours = {
      "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
      "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  std::vector<std::string> groups;
  std::set<std::string> titled_groups;
  std::vector<std::vector<double>> all_y;
  for (const CurvesFigure::Curve& curve : figure.curves) all_y.push_back(curve.y);
  std::ostringstream script;
  script << terminal_line(gnuplot, figure.output, 1000, 600);
  script << "set grid\nset format x '%.1s%c'\n" << kLineAxes;
  std::ostringstream plots;
  for (std::size_t c = 0; c < figure.curves.size(); ++c) {
    const CurvesFigure::Curve& curve = figure.curves[c];
    const std::string block = "$curve" + std::to_string(c);
    script << block << " << EOD\n";
    for (std::size_t i = 0; i < curve.x.size() && i < curve.y.size(); ++i) {
      if (!std::isnan(curve.y[i])) script << curve.x[i] << ' ' << curve.y[i] << '\n';
    }
    script << "EOD\n";
    auto found = std::find(groups.begin(), groups.end(), curve.group);
    if (found == groups.end()) found = groups.insert(groups.end(), curve.group);
    const auto group = static_cast<std::size_t>(found - groups.begin());
    const bool titled = !curve.faint && titled_groups.insert(curve.group).second;
    // Faint curves: alpha 0x66 (#AARRGGBB) and a thin line.
    const std::string colour = kColours[group % kColours.size()];
    plots << (c ? ", " : "") << block << " using 1:2 with lines lw " << (curve.faint ? "1" : "2")
          << " lc rgb '" << (curve.faint ? "#66" + colour.substr(1) : colour) << "' "
          << (titled ? "title " + quoted(curve.group) : std::string("notitle"));
  }
  script << "set output " << quoted(aside.add(figure.output)) << '\n';
  script << "set title " << quoted(figure.title) << '\n';
  script << "set xlabel " << quoted(figure.x_label) << '\n';
  script << "set ylabel " << quoted(figure.y_label) << '\n';
  const std::string y_range = flat_series_range(all_y);
  if (!y_range.empty()) script << "set yrange " << y_range << '\n';
  if (figure.curves.empty()) {
    script << "set label 'no data yet' at graph 0.5, 0.5 center\nplot [0:1] [0:1] NaN notitle\n";
  } else {
    script << "plot " << plots.str() << '\n';
  }
  script << "unset output\n";
  run_gnuplot(gnuplot, script.str(), aside);
}

void draw_heat_maps(const std::vector<HeatMapFigure>& figures) {
  const std::string gnuplot = find_gnuplot();
  FiguresAside aside;
  std::ostringstream script;
  script << "set palette defined (0 '#d73027', 50 '#fee08b', 100 '#1a9850')\n"
            "set cbrange [0:100]\nset cblabel 'success rate [%]'\nunset key\n";
  for (std::size_t f = 0; f < figures.size(); ++f) {
    const HeatMapFigure& figure = figures[f];
    const std::size_t columns = figure.x_values.size();
    const std::size_t rows = figure.y_values.size();
    if (figure.values.size() != rows * columns) {
      throw std::invalid_argument("heat map " + figure.title + ": values do not fill the grid");
    }
    script << terminal_line(gnuplot, figure.output, 900, 600);
    const std::string block = "$map" + std::to_string(f);
    script << block << " << EOD\n";
    for (std::size_t r = 0; r < rows; ++r) {
      for (std::size_t c = 0; c < columns; ++c) {
        script << c << ' ' << r << ' ' << figure.values[r * columns + c] << '\n';
      }
    }
    script << "EOD\n";
    script << "set output " << quoted(aside.add(figure.output)) << '\n';
    script << "set title " << quoted(figure.title) << '\n';
    script << "set xlabel " << quoted(figure.x_label) << '\n';
    script << "set ylabel " << quoted(figure.y_label) << '\n';
    script << "set xrange [-0.5:" << columns - 0.5 << "]\nset yrange [-0.5:" << rows - 0.5 << "]\n";
    script << "set xtics (";
    for (std::size_t c = 0; c < columns; ++c) {
      script << (c ? ", " : "") << tic_label(figure.x_values[c]) << ' ' << c;
    }
    script << ")\nset ytics (";
    for (std::size_t r = 0; r < rows; ++r) {
      script << (r ? ", " : "") << tic_label(figure.y_values[r]) << ' ' << r;
    }
    script << ")\n";
    // One filled box per cell: `with image` needs two rows and two columns to size its
    // pixels, and drew nothing for a one-dimensional grid.
    script << "plot " << block
           << " using 1:2:($1-0.5):($1+0.5):($2-0.5):($2+0.5):3 with boxxy fillcolor palette "
              "fillstyle solid 1.0 noborder, "
           << block << " using 1:2:(sprintf('%.0f', $3)) with labels font ',10'\n";
    script << "unset output\n";
  }
  run_gnuplot(gnuplot, script.str(), aside);
}

}  // namespace upkie_rl::apps
