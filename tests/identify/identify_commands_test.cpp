// configs/identify_commands.csv, the excitation script of `upkie-rl identify`: about 60 s,
// within the velocity task's command ranges with a real robot's margins, and varied enough.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "envs/tasks/velocity_command_schedule.hpp"

namespace upkie_rl {
namespace {

TEST(IdentifyCommands, SixtySecondsWithinTheVelocityTaskRanges) {
  const VelocityCommandRanges ranges;  // the task's: +-1 m/s, +-1.5 rad/s
  const auto schedule = VelocityCommandSchedule::load(
      std::string(UPKIE_RL_SOURCE_DIR) + "/configs/identify_commands.csv", ranges);
  const auto& rows = schedule.rows();
  ASSERT_GE(rows.size(), 20u);
  EXPECT_GE(rows.back().time, 55.0);
  EXPECT_LE(rows.back().time, 65.0);
  double fastest = 0.0, fastest_turn = 0.0, shortest_hold = 1e9;
  bool backward = false, right_turn = false;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const VelocityCommand& command = rows[i].command;
    fastest = std::max(fastest, std::abs(command.forward_velocity));
    fastest_turn = std::max(fastest_turn, std::abs(command.yaw_rate));
    backward = backward || command.forward_velocity < 0.0;
    right_turn = right_turn || command.yaw_rate < 0.0;
    if (i > 0) shortest_hold = std::min(shortest_hold, rows[i].time - rows[i - 1].time);
  }
  // Margins for a real robot, yet brisk enough to make the tires work.
  EXPECT_LE(fastest, 0.8 * ranges.max_forward_velocity);
  EXPECT_GE(fastest, 0.5 * ranges.max_forward_velocity);
  EXPECT_LE(fastest_turn, 0.8 * ranges.max_yaw_rate);
  EXPECT_GT(fastest_turn, 0.0);
  EXPECT_TRUE(backward);
  EXPECT_TRUE(right_turn);
  // Reversals within a second: the actuation's delay and lag show.
  EXPECT_LE(shortest_hold, 0.5);
}

}  // namespace
}  // namespace upkie_rl
