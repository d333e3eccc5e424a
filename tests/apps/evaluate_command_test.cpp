/// `upkie-rl evaluate` from the real binary: the table of a tiny grid, its JSON and heat
/// maps, and clear errors on bad grids.

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/cli_runner.hpp"
#include "common/image_pixels.hpp"
#include "common/temp_files.hpp"

namespace upkie_rl {
namespace {

using testing::count_pixels_near;
using testing::run_cli;
using testing::temp_path;

std::string last_line(std::string text) {
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return text.substr(text.rfind('\n') + 1);
}

TEST(EvaluateCommand, TinyGridGivesTheTableJsonAndHeatMaps) {
  const auto output = temp_path("evaluate");
  const auto result = run_cli(
      "evaluate --env Upkie-MuJoCo-Pendulum --controller pd=linear:10,1,0,0.1 "
      "--controller zero --grid push=0:60:60 --episodes 2 --threads 2 --json --output " +
      output.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  // The PD law survives no push and falls to a 60 N one; the zero controller always falls.
  // The table says which start the episodes had: the evaluations' random one by default.
  EXPECT_NE(result.output.find("pd (success rate over 2 episodes per cell from random starts)"),
            std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("0                 100%"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("60                  0%"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("overall 50% (2/4 episodes)"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("overall 0% (0/4 episodes)"), std::string::npos) << result.output;
  const nlohmann::json summary = nlohmann::json::parse(last_line(result.output));
  ASSERT_EQ(summary["controllers"].size(), 2u);
  EXPECT_EQ(summary["controllers"][0]["start"], "from random starts");
  EXPECT_EQ(summary["controllers"][0]["cells"][0]["successes"], 2);
  EXPECT_EQ(summary["controllers"][0]["cells"][1]["successes"], 0);
  EXPECT_EQ(summary["axes"][0]["values"], nlohmann::json({0.0, 60.0}));
  EXPECT_TRUE(std::filesystem::exists(output / "summary.json"));
  EXPECT_TRUE(std::filesystem::exists(output / "table.txt"));
  for (const char* name : {"heatmap_pd.png", "heatmap_zero.png"}) {
    EXPECT_GT(std::filesystem::file_size(output / name), 1000u) << name;
  }
  // The one-dimensional grid is drawn (it came out blank): pd's cells are green (100%) and
  // red (0%), the zero controller's both red. A cell is about 300 x 200 pixels; the colour
  // bar holds a few hundred pixels of each.
  constexpr std::uint32_t kGreen = 0x1a9850;
  constexpr std::uint32_t kRed = 0xd73027;
  EXPECT_GT(count_pixels_near(output / "heatmap_pd.png", kGreen), 10000);
  EXPECT_GT(count_pixels_near(output / "heatmap_pd.png", kRed), 10000);
  EXPECT_LT(count_pixels_near(output / "heatmap_zero.png", kGreen), 2000);
  EXPECT_GT(count_pixels_near(output / "heatmap_zero.png", kRed), 20000);
  std::filesystem::remove_all(output);
}

TEST(EvaluateCommand, ResultsDoNotDependOnTheThreadCount) {
  const std::string command =
      "evaluate --env Upkie-MuJoCo-Pendulum --controller linear:10,1,0,0.1 "
      "--grid push=0:40:20,mass=0.8:1.2:0.4 --episodes 2 --json --threads ";
  const auto one = run_cli(command + "1");
  const auto two = run_cli(command + "2");
  const auto none = run_cli(command + "0");  // the calling thread alone, as in bench
  ASSERT_EQ(one.exit_code, 0) << one.output;
  EXPECT_EQ(last_line(one.output), last_line(two.output));
  EXPECT_EQ(last_line(one.output), last_line(none.output));
  EXPECT_EQ(last_line(one.output).front(), '{');
}

TEST(EvaluateCommand, BadGridsAndMissingControllersAreNamed) {
  const std::string base = "evaluate --env Upkie-MuJoCo-Pendulum --controller zero --grid ";
  const auto expect_error = [](const testing::CliResult& result, const std::string& part) {
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find(part), std::string::npos) << result.output;
  };
  expect_error(run_cli(base + "push=40:0:5"), "need start <= stop");
  expect_error(run_cli(base + "push=a:b:c"), "\"a\" is not a finite number");
  expect_error(run_cli(base + "push=0:10:5,mass=1,friction=1"), "at most two");
  expect_error(run_cli(base + "push"), "expected name=start:stop:step");
  expect_error(run_cli(base + "warp=1"), "unknown option \"warp\"");
  expect_error(run_cli("evaluate --env Upkie-MuJoCo-Pendulum"), "nothing to evaluate");
  expect_error(run_cli("evaluate --env Upkie-MuJoCo-Servos --controller lqr"),
               "no \"theta\" component");
}

TEST(EvaluateCommand, LqrIsDesignedOnceAndEvaluated) {
  const auto result =
      run_cli("evaluate --env Upkie-MuJoCo-Pendulum --controller lqr --grid push=0 --episodes 2");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("lqr: linear:"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("overall 100% (2/2 episodes)"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace upkie_rl
