/// `upkie-rl drive` from the command line (the browser side is web/viewer/tests/drive.test.mjs):
/// a run without a page stands still and records the command and the measured velocity;
/// its record replays in `view` with the command charts; environments that are not velocity
/// tasks are refused.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "apps/cli_runner.hpp"
#include "common/csv_fields.hpp"
#include "common/temp_files.hpp"

namespace upkie_rl {
namespace {

using testing::read_bytes;
using testing::run_cli;
using testing::temp_path;

TEST(DriveCommand, ARunWithoutADriverStandsStillAndRecordsCommandAndVelocity) {
  const auto record = temp_path("drive.csv");
  const auto result = run_cli(
      "drive --env Upkie-MuJoCo-Velocity --controller lqr --view-port 0 --view-speed 10 "
      "--duration 1 --record " +
      record.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("drive: 50 steps (1 s simulated), 1 episode(s), 0 fall(s)"),
            std::string::npos)
      << result.output;
  std::ifstream in(record);
  std::string line;
  std::getline(in, line);
  std::unordered_map<std::string, std::size_t> column;
  const std::vector<std::string> header = testing::csv_fields(line);
  for (std::size_t i = 0; i < header.size(); ++i) column[header[i]] = i;
  for (const char* name : {"command.forward_velocity", "command.yaw_rate",
                           "measured.forward_velocity", "measured.yaw_rate"}) {
    ASSERT_EQ(column.count(name), 1u) << name << " in " << line;
  }
  int rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    const std::vector<std::string> fields = testing::csv_fields(line);
    ASSERT_EQ(fields.size(), header.size()) << line;
    EXPECT_EQ(std::stod(fields[column["command.forward_velocity"]]), 0.0);
    EXPECT_EQ(std::stod(fields[column["command.yaw_rate"]]), 0.0);
    // Standing: the base stays near its start; the measured velocity is recorded.
    EXPECT_LT(std::hypot(std::stod(fields[column["base_x"]]), std::stod(fields[column["base_y"]])),
              0.1);
    EXPECT_TRUE(std::isfinite(std::stod(fields[column["measured.forward_velocity"]])));
    EXPECT_TRUE(std::isfinite(std::stod(fields[column["measured.yaw_rate"]])));
  }
  EXPECT_EQ(rows, 50);

  // The replay shows the command against the measured velocity.
  const auto html = temp_path("drive.html");
  const auto replay = run_cli("view " + record.string() + " --html " + html.string());
  ASSERT_EQ(replay.exit_code, 0) << replay.output;
  const std::string page = read_bytes(html);
  EXPECT_NE(page.find("\"Forward velocity [m/s]\""), std::string::npos);
  EXPECT_NE(page.find("\"measured.yaw_rate\""), std::string::npos);
  std::filesystem::remove(html);
  std::filesystem::remove(record);
}

TEST(DriveCommand, RefusesAnEnvironmentThatIsNotAVelocityTask) {
  const auto result = run_cli("drive --env Upkie-MuJoCo-Pendulum --view-port 0 --duration 1");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("drive needs a velocity task (Upkie-*-Velocity)"), std::string::npos)
      << result.output;
}

}  // namespace
}  // namespace upkie_rl
