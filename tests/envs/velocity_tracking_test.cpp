#include "envs/tasks/velocity_tracking.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/child_call.hpp"
#include "common/temp_files.hpp"
#include "envs/evaluation/episode_runner.hpp"
#include "envs/tasks/velocity_command_sampler.hpp"
#include "envs/tasks/velocity_command_schedule.hpp"

namespace upkie_rl {
namespace {

TEST(VelocityTracking, RmsOfAHandBuiltTrajectory) {
  // Commands 1 m/s and 0.5 rad/s; measured errors 0.1, -0.3 (vx) and 0.2, 0.0 (wz).
  VelocityTracking tracking;
  tracking.add({1.0, 0.5}, {0.9, 0.3});
  tracking.add({1.0, 0.5}, {1.3, 0.5});
  EXPECT_EQ(tracking.steps, 2);
  EXPECT_NEAR(tracking.rms_forward(), std::sqrt((0.01 + 0.09) / 2), 1e-12);
  EXPECT_NEAR(tracking.rms_yaw(), std::sqrt(0.04 / 2), 1e-12);
  // Without a ramp the target is the command: the same figures both ways.
  EXPECT_DOUBLE_EQ(tracking.rms_forward_target(), tracking.rms_forward());
  EXPECT_DOUBLE_EQ(tracking.rms_yaw_target(), tracking.rms_yaw());
}

TEST(VelocityTracking, AgainstTheFollowedCommandAndAgainstTheTarget) {
  // A ramp toward 1 m/s: followed commands 0.2 and 0.4, measured 0.1 and 0.4; yaw target
  // 1 rad/s reached.
  VelocityTracking tracking;
  tracking.add({0.2, 1.0}, {1.0, 1.0}, {0.1, 0.9});
  tracking.add({0.4, 1.0}, {1.0, 1.0}, {0.4, 1.0});
  EXPECT_NEAR(tracking.rms_forward(), std::sqrt(0.01 / 2), 1e-12);
  EXPECT_NEAR(tracking.rms_forward_target(), std::sqrt((0.81 + 0.36) / 2), 1e-12);
  EXPECT_NEAR(tracking.rms_yaw(), std::sqrt(0.01 / 2), 1e-12);
  EXPECT_NEAR(tracking.rms_yaw_target(), tracking.rms_yaw(), 1e-12);
  VelocityTracking pooled;
  pooled += tracking;
  pooled += tracking;
  EXPECT_NEAR(pooled.rms_forward_target(), tracking.rms_forward_target(), 1e-12);
  EXPECT_EQ(pooled.steps, 4);
}

TEST(VelocityTracking, SummaryPoolsStepsAndCountsFalls) {
  EpisodeOutcome up, fell;
  up.tracking.add({0.5, 0.0}, {0.5, 0.0});
  up.tracking.add({0.5, 0.0}, {0.5, 0.0});
  up.tracking.add({0.5, 0.0}, {0.5, 0.0});
  fell.terminated = true;
  fell.tracking.add({0.0, 1.0}, {0.0, 0.0});  // the steps before the fall count...
  fell.tracking.active = true;                // ...its falling step does not
  const EpisodeSummary summary = summarize_episodes({up, fell});
  ASSERT_TRUE(summary.has_tracking);
  EXPECT_EQ(summary.tracking.steps, 4);
  EXPECT_NEAR(summary.tracking.rms_forward(), 0.0, 1e-12);
  EXPECT_NEAR(summary.tracking.rms_yaw(), std::sqrt(1.0 / 4), 1e-12);
  EXPECT_DOUBLE_EQ(summary.fall_rate, 0.5);
  EXPECT_FALSE(summarize_episodes({EpisodeOutcome{}}).has_tracking);
}

TEST(VelocityCommandSchedule, PiecewiseConstantCommands) {
  const VelocityCommandSchedule schedule({{0.0, {0.0, 0.0}}, {1.0, {0.5, 0.1}}, {3.0, {-1, 0}}});
  EXPECT_EQ(schedule.at(0.0), (VelocityCommand{0.0, 0.0}));
  EXPECT_EQ(schedule.at(0.99), (VelocityCommand{0.0, 0.0}));
  EXPECT_EQ(schedule.at(1.0), (VelocityCommand{0.5, 0.1}));
  EXPECT_EQ(schedule.at(2.5), (VelocityCommand{0.5, 0.1}));
  EXPECT_EQ(schedule.at(100.0), (VelocityCommand{-1.0, 0.0}));
  using Rows = std::vector<VelocityCommandSchedule::Row>;
  EXPECT_THROW(VelocityCommandSchedule(Rows{}), std::invalid_argument);
  EXPECT_THROW(VelocityCommandSchedule(Rows{{1.0, {}}, {1.0, {}}}), std::invalid_argument);
  EXPECT_THROW(VelocityCommandSchedule(Rows{{0.0, {NAN, 0.0}}}), std::invalid_argument);
}

/// The velocity task's default command ranges: +-1 m/s, +-1.5 rad/s.
const VelocityCommandRanges kRanges;

TEST(VelocityCommandSchedule, LoadsACsvAndNamesTheBadLine) {
  const auto good = testing::temp_path("good.csv");
  std::ofstream(good) << "time,vx,wz\n# comment\n0,0,0\n\n2.5, 0.8 ,-0.4\n";
  const VelocityCommandSchedule schedule = VelocityCommandSchedule::load(good, kRanges);
  ASSERT_EQ(schedule.rows().size(), 2u);
  EXPECT_EQ(schedule.at(3.0), (VelocityCommand{0.8, -0.4}));
  // configs/velocity_commands.csv's layout: comments before the header.
  const auto commented = testing::temp_path("commented.csv");
  std::ofstream(commented) << "# commands\n\ntime,vx,wz\n0,0.5,1\n";
  EXPECT_EQ(VelocityCommandSchedule::load(commented, kRanges).at(0.0), (VelocityCommand{0.5, 1.0}));
  const auto bad = testing::temp_path("bad.csv");
  std::ofstream(bad) << "time,vx,wz\n0,0,0\n1,fast,0\n";
  try {
    VelocityCommandSchedule::load(bad, kRanges);
    FAIL() << "a malformed row was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("bad.csv:3"), std::string::npos) << error.what();
  }
  EXPECT_THROW(VelocityCommandSchedule::load(testing::temp_path("missing.csv"), kRanges),
               std::invalid_argument);
}

/// What loading `text` as a command file within kRanges throws ("" if nothing).
std::string load_error(const std::string& text) {
  const auto path = testing::temp_path("bounds.csv");
  testing::write_bytes(path, text);
  try {
    VelocityCommandSchedule::load(path, kRanges);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(VelocityCommandSchedule, RefusesValuesOutsideTheTasksRangesNamingLineColumnAndValue) {
  const std::string path = testing::temp_path("bounds.csv").string();
  EXPECT_EQ(load_error("time,vx,wz\n0,1,-1.5\n1,-1,1.5\n"), "");
  EXPECT_EQ(load_error("time,vx,wz\n0,0,0\n1,1e30,0\n"),
            path + ":3: column vx (env option max_forward_velocity): 1e+30 is outside [-1, 1]");
  EXPECT_EQ(load_error("time,vx,wz\n0,1e39,0\n"),
            path + ":2: column vx (env option max_forward_velocity): 1e+39 is outside [-1, 1]");
  EXPECT_EQ(load_error("0,0,-1.6\n"),
            path + ":1: column wz (env option max_yaw_rate): -1.6 is outside [-1.5, 1.5]");
  EXPECT_EQ(load_error("0,0,nan\n"),
            path +
                ":1: column wz (env option max_yaw_rate): nan is not a finite number; "
                "expected one in [-1.5, 1.5]");
  EXPECT_EQ(load_error("0,0,0\n1e10,0,0\n"), path + ":2: column time: 1e+10 is outside [0, 1e+09]");
  EXPECT_EQ(load_error("-1,0,0\n"), path + ":1: column time: -1 is outside [0, 1e+09]");
}

TEST(VelocityCommandSchedule, RefusesADeviceAndAFifoPromptly) {
  const auto fifo = testing::make_fifo(testing::temp_path("commands.fifo"));
  ASSERT_FALSE(fifo.empty());
  for (const std::filesystem::path& path : {std::filesystem::path("/dev/zero"), fifo}) {
    EXPECT_EQ(testing::child_call_error([&] { VelocityCommandSchedule::load(path, kRanges); }),
              "velocity commands " + path.string() +
                  ": not a regular file (a FIFO, a device or a socket)");
  }
}

}  // namespace
}  // namespace upkie_rl
