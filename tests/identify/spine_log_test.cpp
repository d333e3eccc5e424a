// Spine logs (mpacklog) and record files read back for identification: what they hold, and
// the one-line refusals of broken logs.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "common/temp_files.hpp"
#include "envs/records/robot_log.hpp"
#include "identify/excitation_log.hpp"
#include "identify/log_replay.hpp"
#include "spine/spine_log_reader.hpp"
#include "spine/spine_log_writer.hpp"

namespace upkie_rl {
namespace {

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

Observation observation_at(double time) {
  Observation observation;
  observation.time = time;
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    observation.servo[servo].position = 0.1 * static_cast<double>(servo) + time;
    observation.servo[servo].velocity = -0.5 * static_cast<double>(servo);
  }
  observation.base_orientation.pitch = 0.02;
  observation.base_orientation.angular_velocity = Eigen::Vector3d(0.0, 0.3, 0.0);
  return observation;
}

std::filesystem::path write_small_log(const std::string& name, int cycles = 5) {
  const std::filesystem::path path = testing::temp_path(name);
  SpineLogWriter writer(path);
  ServoAction action{};
  for (int i = 0; i < cycles; ++i) {
    action[kLeftWheel].velocity = 1.5 * i;
    action[kLeftWheel].maximum_torque = 1.7;
    writer.write(observation_at(0.005 * i), action);
  }
  writer.close();
  return path;
}

/// The message of the RobotLogError that reading `bytes` raises, or "" when none.
std::string spine_log_refusal(const std::string& bytes) {
  try {
    read_spine_log(bytes, "test.mpack");
  } catch (const RobotLogError& error) {
    return error.what();
  }
  return "";
}

/// A 1 kHz log whose commands change at `phase` ms into each 20 ms step (positions NaN,
/// as a wheel's "no position loop").
RobotLog log_written_at_phase(std::size_t phase) {
  RobotLog log;
  for (std::size_t i = 0; i < 400; ++i) {
    LoggedCycle& cycle = log.cycles.emplace_back();
    cycle.time = 1e-3 * static_cast<double>(i);
    const std::size_t step = (i + 20 - phase) / 20;  // the step whose command is in force
    for (ServoCommand& servo : cycle.command) servo.velocity = 0.1 * static_cast<double>(step);
  }
  return log;
}

TEST(AgentPhase, IsTheCycleOfEachStepWhereTheCommandsChange) {
  EXPECT_EQ(agent_phase(log_written_at_phase(5), 20), 5u);
  EXPECT_EQ(agent_phase(log_written_at_phase(0), 20), 0u);
  EXPECT_EQ(agent_phase(log_written_at_phase(17), 20), 17u);
  // Commands that never change (NaN positions included) leave the phase at 0.
  RobotLog still = log_written_at_phase(5);
  for (LoggedCycle& cycle : still.cycles) cycle.command = still.cycles.front().command;
  EXPECT_EQ(agent_phase(still, 20), 0u);
}

TEST(SpineLog, WrittenCyclesReadBack) {
  const auto path = write_small_log("round_trip.mpack");
  const RobotLog log = read_robot_log(path);
  EXPECT_EQ(log.format, "spine log");
  ASSERT_EQ(log.cycles.size(), 5u);
  EXPECT_DOUBLE_EQ(log.cycles[3].time, 0.015);
  EXPECT_DOUBLE_EQ(log.cycles[3].observation.servo[kRightHip].position, 0.3 + 0.015);
  EXPECT_DOUBLE_EQ(log.cycles[3].command[kLeftWheel].velocity, 4.5);
  EXPECT_TRUE(std::isnan(log.cycles[3].command[kLeftHip].position));
  EXPECT_NEAR(log.period(), 0.005, 1e-12);
}

TEST(SpineLog, TruncatedStreamIsRefused) {
  std::string bytes = read_bytes(write_small_log("truncated.mpack"));
  bytes.resize(bytes.size() - 40);
  const std::string message = spine_log_refusal(bytes);
  EXPECT_NE(message.find("truncated mpack stream"), std::string::npos) << message;
  EXPECT_NE(message.find("dictionary 4"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
}

TEST(SpineLog, HugeAndNanValuesAreRefused) {
  const std::string bytes = read_bytes(write_small_log("values.mpack"));
  // The float64 of pitch (0.02) in the second dictionary, replaced by 1e308, then NaN.
  double pitch = 0.02;
  std::string needle(8, '\0');
  for (int i = 0; i < 8; ++i) needle[i] = reinterpret_cast<const char*>(&pitch)[7 - i];
  const std::size_t first = bytes.find(needle);
  const std::size_t second = bytes.find(needle, first + 1);
  ASSERT_NE(second, std::string::npos);
  for (double bad : {1e308, std::nan("")}) {
    std::string damaged = bytes;
    for (int i = 0; i < 8; ++i) damaged[second + i] = reinterpret_cast<const char*>(&bad)[7 - i];
    const std::string message = spine_log_refusal(damaged);
    EXPECT_NE(message.find("base_orientation.pitch"), std::string::npos) << message;
    EXPECT_NE(message.find("dictionary 1"), std::string::npos) << message;
  }
}

TEST(SpineLog, MissingKeyIsRefused) {
  std::string bytes = read_bytes(write_small_log("missing.mpack"));
  const std::size_t key = bytes.find("wheel_odometry");
  ASSERT_NE(key, std::string::npos);
  bytes[key] = 'x';  // the key no longer exists
  const std::string message = spine_log_refusal(bytes);
  EXPECT_NE(message.find("wheel_odometry"), std::string::npos) << message;
}

TEST(SpineLog, ReadsALogWrittenByPythonMpacklog) {
  // tests/data/logs/mpacklog_python.mpack: written by tests/data/logs/make_mpacklog_python.py with
  // mpacklog.SyncLogger (Python ints and floats, as Upkie's Python tools log).
  const RobotLog log =
      read_robot_log(std::string(UPKIE_RL_TEST_DATA_DIR) + "/logs/mpacklog_python.mpack");
  ASSERT_EQ(log.cycles.size(), 3u);
  EXPECT_DOUBLE_EQ(log.cycles[2].time, 0.01);
  EXPECT_DOUBLE_EQ(log.cycles[2].observation.servo[kLeftWheel].velocity, 2.0);
  EXPECT_DOUBLE_EQ(log.cycles[2].command[kRightWheel].velocity, -3.0);
  EXPECT_DOUBLE_EQ(log.cycles[1].observation.base_orientation.pitch, 0.05);
}

TEST(RecordLog, MissingColumnNanRowAndWrongFrequencyAreRefused) {
  const auto refusal = [](const std::string& text) -> std::string {
    try {
      read_record_log(text, "test.csv").check_regular();
    } catch (const RobotLogError& error) {
      return error.what();
    }
    return "";
  };
  const std::string header = "episode,step,t,pitch,ground_position,theta_dot\n";
  EXPECT_NE(refusal("episode,step,t,ground_position\n0,0,0,0\n").find("no column \"pitch\""),
            std::string::npos);
  EXPECT_NE(refusal(header + "0,0,0,0,0,0\n0,1,0.005,nan,0,0\n").find("pitch is NaN"),
            std::string::npos);
  EXPECT_NE(refusal(header + "0,0,0,0,0,0\n0,1,0.005,1e308,0,0\n").find("corrupt"),
            std::string::npos);
  EXPECT_NE(refusal(header + "0,0,0,0,0,0\n0,1,0.005,0,0,0\n0,2,0.010,0,0,0\n0,3,0.030,0,0,0\n")
                .find("another frequency"),
            std::string::npos);
  const RobotLog log = read_record_log(header + "0,0,0,0.1,0,0.2\n0,1,0.005,0.1,0,0.2\n", "ok.csv");
  EXPECT_TRUE(log.signals.pitch_rate);
  EXPECT_FALSE(log.signals.servo_commands);
}

}  // namespace
}  // namespace upkie_rl
