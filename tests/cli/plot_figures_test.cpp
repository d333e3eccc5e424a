/// The pieces of figures and progress lines that do not need gnuplot or a terminal.

#include <gtest/gtest.h>

#include <cmath>

#include "cli/gnuplot_figure.hpp"
#include "cli/progress_bar.hpp"
#include "cli/robustness_grid.hpp"
#include "cli/smoothing_window.hpp"

namespace upkie_rl::apps {
namespace {

TEST(FlatSeriesRange, FlatDataGetsTenPercentAroundItsValue) {
  // A constant series with floating-point noise: without a range gnuplot zooms into 1e-12.
  EXPECT_EQ(flat_series_range({{0.01, 0.01}}), "[0.0090000000000000011:0.010999999999999999]");
  EXPECT_FALSE(flat_series_range({{0.01, 0.01 + 1e-12, 0.01}}).empty());
  EXPECT_EQ(flat_series_range({{0.0, 0.0}, {NAN}}), "[-1:1]");
  EXPECT_EQ(flat_series_range({{-300.0, -300.0}}), "[-330:-270]");
  // Varying data, and no data, are left to gnuplot.
  EXPECT_EQ(flat_series_range({{1.0, 2.0}}), "");
  EXPECT_EQ(flat_series_range({{NAN}}), "");
}

TEST(SmoothingWindow, FitsATenthOfTheRun) {
  // The 148-update run whose 50-update mean ended 60 below the raw return: 14 updates.
  EXPECT_EQ(fitted_window(50, 148), 14u);
  EXPECT_EQ(fitted_window(50, 10'000), 50u);  // a long run keeps the window asked
  EXPECT_EQ(fitted_window(5, 148), 5u);
  EXPECT_EQ(fitted_window(50, 3), 1u);  // a few updates: drawn as they are
  for (std::size_t updates = 1; updates < 2000; ++updates) {
    EXPECT_LE(fitted_window(50, updates), std::max<std::size_t>(1, updates / 10)) << updates;
  }
  EXPECT_EQ(smoothing_label(14), "mean of the last 14 updates (lags about 7)");
}

TEST(HeatMapAxes, EveryAxisHasAUnit) {
  EXPECT_EQ(axis_label("push", "Upkie-MuJoCo-Pendulum"), "push [N]");
  EXPECT_EQ(axis_label("mass", "Upkie-MuJoCo-Pendulum"), "mass [x nominal]");
  EXPECT_EQ(axis_label("pitch", "Upkie-MuJoCo-Pendulum"), "initial pitch bound [rad]");
  // Another option: the unit its help states, or none.
  EXPECT_EQ(axis_label("frequency", "Upkie-MuJoCo-Pendulum"), "frequency [Hz]");
  EXPECT_EQ(axis_label("push_force", "Upkie-MuJoCo-Pendulum"), "push_force [N]");
  EXPECT_EQ(axis_label("mass_scale", "Upkie-MuJoCo-Pendulum"), "mass_scale [dimensionless]");
  for (const char* name : {"push", "mass", "friction", "lag", "delay", "pitch"}) {
    EXPECT_NE(axis_label(name, "Upkie-MuJoCo-Pendulum").find('['), std::string::npos) << name;
  }
}

TEST(ProgressLine, FitsTheWidthAndDropsFieldsInOrder) {
  const auto line = [](int columns) {
    return progress_line(0.5, "512,000", "1,024,000", "4,321", "01:58", "return -12.3", columns);
  };
  const std::string wide = line(200);
  EXPECT_EQ(wide,
            "[###############...............]  50% 512,000/1,024,000 steps | return -12.3 | "
            "4,321 steps/s | ETA 01:58");
  for (int columns = 10; columns <= 120; ++columns) {
    EXPECT_LE(static_cast<int>(line(columns).size()), columns) << columns;
  }
  // 60 columns (one spare): the bar shrinks, ETA and speed go, the return stays.
  EXPECT_EQ(line(59), "[######.......]  50% 512,000/1,024,000 steps | return -12.3");
  EXPECT_EQ(line(40), " 50% 512,000/1,024,000 steps");
}

}  // namespace
}  // namespace upkie_rl::apps
