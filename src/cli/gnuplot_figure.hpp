#pragma once
/// @file
/// Line figures drawn by gnuplot (pngcairo, or png when cairo is missing; SVG for an output
/// named *.svg), fed through a pipe: a raw series drawn semi-transparent and its rolling
/// mean on top. Text is drawn as given (gnuplot's "enhanced" markup is off).

#include <filesystem>
#include <string>
#include <vector>

namespace upkie_rl::apps {

/// One figure: y against x, raw and smoothed.
struct TrendFigure {
  std::filesystem::path output;  ///< PNG file to write (SVG when named *.svg).
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<double> x;
  std::vector<double> raw;       ///< NaN values are left out.
  std::vector<double> smoothed;  ///< Same size as raw.
  std::string smoothed_label;    ///< e.g. "rolling mean (50)".
};

/// A heat map of values in [0, 100] (percentages) over a grid of at most two axes, each
/// cell labelled with its value.
struct HeatMapFigure {
  std::filesystem::path output;  ///< PNG file to write (SVG when named *.svg).
  std::string title;
  std::string x_label;
  std::vector<std::string> x_values;  ///< Column labels.
  std::string y_label;                ///< Empty for a single row.
  std::vector<std::string> y_values;  ///< Row labels (one empty label for a single row).
  std::vector<double> values;         ///< Row-major, y_values.size() x x_values.size().
};

/// Curves of several runs on one figure (a sweep's return curves): the curves of one group
/// share a colour, and each group is named once in the key.
struct CurvesFigure {
  struct Curve {
    std::string group;
    std::vector<double> x;
    std::vector<double> y;  ///< NaN values are left out.
    bool faint = false;     ///< Thin and semi-transparent, never in the key (raw values).
  };
  std::filesystem::path output;  ///< PNG file to write (SVG when named *.svg).
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<Curve> curves;
};

/// Full path of the gnuplot executable on PATH; throws std::runtime_error saying how to
/// install it when there is none.
std::string find_gnuplot();

/// The y range gnuplot should use for `values` (NaN left out), as "[low:high]", or empty
/// to let gnuplot choose: a flat series (spread below 1e-6 of its magnitude, floating-point
/// noise) gets ±10% of its value (±1 for a zero series) instead of a range zoomed into noise.
std::string flat_series_range(const std::vector<std::vector<double>>& series);

/// Draws the figures in one gnuplot session. Throws std::runtime_error if gnuplot is
/// missing or fails.
void draw_trend_figures(const std::vector<TrendFigure>& figures);

/// Draws the figure. Throws std::runtime_error if gnuplot is missing or fails.
void draw_curves_figure(const CurvesFigure& figure);

/// Draws the heat maps in one gnuplot session (red 0 % to green 100 %). Throws
/// std::runtime_error if gnuplot is missing or fails.
void draw_heat_maps(const std::vector<HeatMapFigure>& figures);

}  // namespace upkie_rl::apps
