// upkie-rl-agent against `upkie-rl spine` in real time: it balances the test policies, and
// every supervisor path (spine killed, spine frozen, robot pushed over, a policy that can
// output NaN in nan_policy_test.cpp, corrupted checkpoint, SIGTERM) ends in stopping with the
// stop commands sent and a clear message, never a crash.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mman.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "agent/agent_spine.hpp"
#include "common/background_process.hpp"
#include "common/temp_files.hpp"
#include "policy/checkpoint_file.hpp"

namespace upkie_rl {
namespace {

using testing::BackgroundProcess;
using testing::expect_supervised_stop;
using testing::kPendulum;
using testing::kServosBalance;
using testing::kStopRequest;
using testing::kVelocity;
using testing::Spine;
using testing::start_agent;
using testing::temp_path;
using testing::wait_running;

/// Runs `model` on a real-time spine of `backend` for `duration` seconds and expects the
/// run to reach its end (the supervisor would stop it at a fall: attitude, pitch limits).
void expect_balances(const std::string& model, const std::string& backend, int duration = 10,
                     double frequency = 200.0) {
  Spine spine("balance_" + backend, {}, backend);
  auto agent =
      start_agent(spine, model, "balance_" + backend, {"--duration", std::to_string(duration)});
  const int status = agent->wait();
  const std::string output = agent->output();
  EXPECT_EQ(status, 0) << output;
  EXPECT_NE(
      output.find("running -> stopping: duration of " + std::to_string(duration) + " s reached"),
      std::string::npos)
      << output;
  EXPECT_NE(output.find("5 of 5 stop cycles answered"), std::string::npos) << output;
  // duration x frequency cycles at most; a loaded 2-core machine runs some late.
  const auto at = output.find("summary: ");
  ASSERT_NE(at, std::string::npos) << output;
  const long cycles = std::stol(output.substr(at + 9));
  const double expected = duration * frequency;
  EXPECT_GT(cycles, 0.75 * expected) << output;
  EXPECT_LT(cycles, expected + 10) << output;
}

TEST(AgentRunner, BalancesThePendulumPolicyTenSeconds) { expect_balances(kPendulum, "bullet"); }

TEST(AgentRunner, BalancesTheServosBalancePolicyTenSeconds) {
  expect_balances(kServosBalance, "mujoco");
}

// One robot, one physics: the velocity task trains on the robot's MuJoCo tires and wheel
// damping, which the simulation spine shares, so the checked-in velocity policy, told to
// stand still, stands there too (it fell within a second when the task had tires of its own).
TEST(AgentRunner, VelocityPolicyStandsTwentySecondsOnTheMujocoSpine) {
  expect_balances(kVelocity, "mujoco", 20, 50.0);
}

TEST(AgentRunner, KilledSpineStopsWithAClearMessage) {
  Spine spine("killed");
  auto agent = start_agent(spine, kPendulum, "killed");
  ASSERT_TRUE(wait_running(*agent)) << agent->output();
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  spine.process().kill();
  EXPECT_EQ(agent->wait(), 2);
  const std::string output = agent->output();
  expect_supervised_stop(output, "spine did not process request within 100 ms");
  EXPECT_NE(output.find("writing Stop"), std::string::npos) << output;
  EXPECT_EQ(spine.request(), kStopRequest);
}

TEST(AgentRunner, FrozenSpineStopsAndFindsStopWhenResumed) {
  Spine spine("frozen");
  auto agent = start_agent(spine, kPendulum, "frozen");
  ASSERT_TRUE(wait_running(*agent)) << agent->output();
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ::kill(spine.process().pid(), SIGSTOP);
  EXPECT_EQ(agent->wait(), 2);
  expect_supervised_stop(agent->output(), "spine did not process request within 100 ms");
  EXPECT_EQ(spine.request(), kStopRequest);  // what the spine reads when it resumes
  ::kill(spine.process().pid(), SIGCONT);
}

TEST(AgentRunner, PushedOverRobotTripsTheAttitudeLimit) {
  Spine spine("pushed", {"--push-force", "300", "--push-time", "1", "--push-duration", "0.3"});
  auto agent = start_agent(spine, kPendulum, "pushed", {"--duration", "10"});
  EXPECT_EQ(agent->wait(), 2);
  const std::string output = agent->output();
  EXPECT_NE(output.find("running -> stopping"), std::string::npos) << output;
  EXPECT_TRUE(output.find("limit") != std::string::npos ||
              output.find("task termination") != std::string::npos)
      << output;
  expect_supervised_stop(output, "");
  EXPECT_NE(output.find("5 of 5 stop cycles answered"), std::string::npos) << output;
}

// A policy whose output can be NaN, refused at load: nan_policy_test.cpp.

TEST(AgentRunner, CorruptedCheckpointIsRefusedBeforeAnythingStarts) {
  std::string bytes = testing::read_bytes(kPendulum);
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x5a);
  const auto corrupted = temp_path("agent_corrupted.ckpt");
  testing::write_bytes(corrupted, bytes);
  Spine spine("corrupted");
  auto agent = start_agent(spine, corrupted.string(), "corrupted");
  EXPECT_EQ(agent->wait(), 2);
  const std::string output = agent->output();
  EXPECT_NE(output.find("idle -> stopping: "), std::string::npos) << output;
  EXPECT_NE(output.find(corrupted.string()), std::string::npos) << output;
  EXPECT_NE(output.find("Stop request sent to the spine"), std::string::npos) << output;
  EXPECT_EQ(output.find("-> running"), std::string::npos) << output;
}

TEST(AgentRunner, SigtermTakesTheStoppingPath) {
  Spine spine("sigterm");
  auto agent = start_agent(spine, kPendulum, "sigterm");
  ASSERT_TRUE(wait_running(*agent)) << agent->output();
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_EQ(agent->wait(SIGTERM), 0);
  const std::string output = agent->output();
  expect_supervised_stop(output, "interrupted (SIGINT or SIGTERM)");
  EXPECT_NE(output.find("5 of 5 stop cycles answered"), std::string::npos) << output;
}

TEST(AgentRunner, DryRunLogsCommandsAndSendsOnlyStops) {
  // With the policy's commands the robot balances 10 s (above); without them, held by the
  // stop commands alone, it falls within a few seconds: proof that they were not sent.
  Spine spine("dry");
  auto agent = start_agent(spine, kPendulum, "dry", {"--duration", "8", "--dry-run"});
  EXPECT_EQ(agent->wait(), 2);
  const std::string output = agent->output();
  EXPECT_NE(output.find("dry run, cycle 0, not sent: left_hip: position"), std::string::npos)
      << output;
  EXPECT_NE(output.find("dry run, cycle 200, not sent: "), std::string::npos) << output;
  expect_supervised_stop(output, "attitude limit: pitch");
}

TEST(AgentRunner, FrozenRunnerTripsTheLoopOverrun) {
  Spine spine("overrun");
  auto agent = start_agent(spine, kPendulum, "overrun", {"--spine-timeout", "5"});
  ASSERT_TRUE(wait_running(*agent)) << agent->output();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ::kill(agent->pid(), SIGSTOP);
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  ::kill(agent->pid(), SIGCONT);
  EXPECT_EQ(agent->wait(), 2);
  expect_supervised_stop(agent->output(), "loop overrun: one cycle took");
}

}  // namespace
}  // namespace upkie_rl
