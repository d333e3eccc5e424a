#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "apps/cli_runner.hpp"

namespace upkie_rl {
namespace {

using testing::run_cli;

bool is_png(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  char signature[8] = {};
  file.read(signature, 8);
  return file && std::string(signature + 1, 3) == "PNG" && std::filesystem::file_size(path) > 1000;
}

TEST(PlotCommand, DrawsTheThreeFiguresFromProgressCsv) {
  const auto run_dir =
      std::filesystem::temp_directory_path() / ("upkie_rl_plot_" + std::to_string(::getpid()));
  std::filesystem::remove_all(run_dir);
  std::filesystem::create_directories(run_dir);
  {
    std::ofstream csv(run_dir / "progress.csv");
    csv << "time/total_timesteps,rollout/ep_rew_mean,train/loss,train/approx_kl\n";
    for (int i = 1; i <= 120; ++i) {
      csv << i * 2040 << "," << (i < 3 ? std::string() : std::to_string(i * 2.0)) << "," << 1.0 / i
          << "," << 0.01 + 0.001 * (i % 7) << "\n";
    }
  }
  const auto result = run_cli("plot " + run_dir.string() + " --window 10");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  for (const char* name : {"loss.png", "kl.png", "return.png"}) {
    EXPECT_TRUE(is_png(run_dir / name)) << name;
  }
  std::filesystem::remove_all(run_dir);
}

TEST(PlotCommand, MissingOrMalformedLogsGiveClearErrors) {
  auto result = run_cli("plot /nonexistent/run");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("no progress.csv"), std::string::npos) << result.output;

  const auto run_dir =
      std::filesystem::temp_directory_path() / ("upkie_rl_plot_bad_" + std::to_string(::getpid()));
  std::filesystem::create_directories(run_dir);
  std::ofstream(run_dir / "progress.csv") << "time/total_timesteps,train/loss\n1,abc\n";
  result = run_cli("plot " + run_dir.string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("not a number"), std::string::npos) << result.output;
  result = run_cli("plot " + run_dir.string() + " --window 0");
  EXPECT_NE(result.exit_code, 0);
  std::filesystem::remove_all(run_dir);
}

}  // namespace
}  // namespace upkie_rl
