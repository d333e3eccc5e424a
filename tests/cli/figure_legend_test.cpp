/// The legends of the line figures: every key entry drawn as its text, in one run, and no
/// text of a figure (key entries, title, axis labels, tick labels) over another. The figures
/// are drawn as SVG, whose text elements give each text's anchor, size and content; a
/// text's box is estimated at 0.6 em per character (wider than sans-serif's average).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli/gnuplot_figure.hpp"
#include "cli/smoothing_window.hpp"

namespace upkie_rl::apps {
namespace {

struct SvgText {
  std::string content;  ///< The element's inner markup.
  double left = 0.0, right = 0.0, top = 0.0, bottom = 0.0;
};

/// The horizontal texts of an SVG written by gnuplot (rotated ones, the y label, left out).
std::vector<SvgText> svg_texts(const std::filesystem::path& path) {
  std::ifstream file(path);
  std::stringstream svg;
  svg << file.rdbuf();
  const std::string text = svg.str();
  static const std::regex element(
      R"re(<g transform="translate\(([-\d.]+),([-\d.]+)\)"[^>]*font-size="([\d.]+)"[^>]*text-anchor="(\w+)">\s*<text>(.*?)</text>)re");
  std::vector<SvgText> texts;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), element);
       it != std::sregex_iterator(); ++it) {
    const std::smatch& match = *it;
    SvgText entry;
    entry.content = match[5];
    const double x = std::stod(match[1]);
    const double y = std::stod(match[2]);
    const double size = std::stod(match[3]);
    const std::string trimmed = std::regex_replace(entry.content, std::regex("^ +| +$"), "");
    const double width = 0.6 * size * static_cast<double>(trimmed.size());
    const std::string anchor = match[4];
    entry.left = anchor == "start" ? x : anchor == "end" ? x - width : x - width / 2;
    entry.right = entry.left + width;
    entry.top = y - size;
    entry.bottom = y + 0.3 * size;
    texts.push_back(entry);
  }
  return texts;
}

bool overlap(const SvgText& a, const SvgText& b) {
  return a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom;
}

/// Every `titles` entry drawn as one text element of exactly that text, and no two texts
/// of the figure over each other.
void expect_legible(const std::filesystem::path& svg, const std::vector<std::string>& titles) {
  const std::vector<SvgText> texts = svg_texts(svg);
  ASSERT_GT(texts.size(), titles.size()) << svg;
  for (const std::string& title : titles) {
    bool drawn = false;
    for (const SvgText& text : texts) drawn = drawn || text.content == title;
    EXPECT_TRUE(drawn) << "\"" << title << "\" is not drawn as one text in " << svg;
  }
  for (std::size_t i = 0; i < texts.size(); ++i) {
    for (std::size_t j = i + 1; j < texts.size(); ++j) {
      EXPECT_FALSE(overlap(texts[i], texts[j]))
          << "\"" << texts[i].content << "\" overlaps \"" << texts[j].content << "\" in " << svg;
    }
  }
}

class FigureLegend : public ::testing::Test {
 protected:
  void SetUp() override {
    try {
      find_gnuplot();
    } catch (const std::runtime_error&) {
      GTEST_SKIP() << "gnuplot is not installed";
    }
    directory_ =
        std::filesystem::temp_directory_path() /
        ("upkie_rl_legend_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
    std::filesystem::create_directories(directory_);
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }
  std::filesystem::path directory_;
};

TEST_F(FigureLegend, TrendFigureKeyIsDrawnAsWrittenAndApart) {
  // The label that gnuplot's enhanced text drew as "(lags 2" with the 5 over the 2.
  TrendFigure figure;
  figure.output = directory_ / "return.svg";
  figure.title = "Mean episode return (last 100 episodes)";
  figure.x_label = "environment steps";
  figure.y_label = "return (dimensionless)";
  for (int i = 0; i < 148; ++i) {
    figure.x.push_back(2048.0 * i);
    figure.raw.push_back(std::sin(0.1 * i) * 100.0 + i);
  }
  figure.smoothed = figure.raw;
  figure.smoothed_label = "mean of the last 50 updates (lags ~25) of run_a";
  draw_trend_figures({figure});
  expect_legible(figure.output, {"raw", figure.smoothed_label, figure.title, figure.x_label});
}

TEST_F(FigureLegend, CurvesFigureKeyOfLongGroupNamesIsApart) {
  CurvesFigure figure;
  figure.output = directory_ / "returns.svg";
  figure.title = "Training return of each run, " + smoothing_label(14);
  figure.x_label = "environment steps";
  figure.y_label = "return (dimensionless)";
  const std::vector<std::string> groups = {"obs_lags 2 (seed 5)", "obs_lags 0 (seed 5)",
                                           "a much longer group name, with ~tildes~ and _"};
  for (std::size_t g = 0; g < groups.size(); ++g) {
    CurvesFigure::Curve curve{groups[g], {}, {}};
    for (int i = 0; i < 50; ++i) {
      curve.x.push_back(1000.0 * i);
      curve.y.push_back(static_cast<double>(g * 10 + i));
    }
    figure.curves.push_back(curve);
  }
  draw_curves_figure(figure);
  std::vector<std::string> titles = groups;
  titles.push_back(figure.title);
  expect_legible(figure.output, titles);
}

}  // namespace
}  // namespace upkie_rl::apps
