/// `upkie-rl train --view` and `upkie-rl spine --view`: frames of the real binary reach a
/// WebSocket client. (`rollout --view` is tested in a browser: web/viewer/tests.)

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "apps/cli_runner.hpp"
#include "common/background_process.hpp"
#include "common/frame_client.hpp"
#include "common/temp_files.hpp"
#include "view/view_frame.hpp"

namespace upkie_rl {
namespace {

using testing::read_bytes;
using testing::temp_path;

/// `upkie-rl <args>` in the background, and the port of the viewer it serves.
class BackgroundCli : public testing::BackgroundProcess {
 public:
  BackgroundCli(std::vector<std::string> args, const std::string& name)
      : BackgroundProcess(with_cli(std::move(args)), name) {}

  /// The port of the "viewer: http://127.0.0.1:PORT/" line, or 0 after 60 s without it.
  int viewer_port() const {
    const auto port = wait_for_line(std::regex("viewer: http://127\\.0\\.0\\.1:([0-9]+)/"));
    return port ? std::stoi(*port) : 0;
  }

  /// Whether the output says it waits for browsers, within 60 s.
  bool says_it_waits_for_browsers() const {
    return wait_for_line(std::regex("viewer: waiting for ([0-9]+) browser")).has_value();
  }

 private:
  /// The first group of the first match of `pattern` in the output, or nothing after 60 s.
  std::optional<std::string> wait_for_line(const std::regex& pattern) const {
    for (int i = 0; i < 6000; ++i) {
      std::smatch match;
      const std::string text = output();
      if (std::regex_search(text, match, pattern)) return match[1].str();
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return std::nullopt;
  }

  static std::vector<std::string> with_cli(std::vector<std::string> args) {
    args.insert(args.begin(), UPKIE_RL_CLI_PATH);
    return args;
  }
};

TEST(LiveViewCommand, TrainingStreamsTheEnvironmentItIsAskedFor) {
  const auto run_dir = temp_path("view_train_run");
  std::filesystem::remove_all(run_dir);
  BackgroundCli train(
      {"train", "--config", std::string(UPKIE_RL_SOURCE_DIR) + "/configs/pendulum.yaml", "--set",
       "ppo.total_timesteps=4096", "--set", "env.num_envs=2", "--quiet", "--run-dir",
       run_dir.string(), "--view", "--view-port", "0", "--view-wait", "1", "--view-env", "1"},
      "view_train");
  const int port = train.viewer_port();
  ASSERT_GT(port, 0) << train.output();
  testing::FrameClient client(port);
  const std::size_t frame_size = view_frame_size(1);
  const std::vector<double> frames = client.read_frames(frame_size, 200);
  ASSERT_GE(frames.size(), 200 * frame_size) << train.output();
  // Steps count up within an episode, times follow the 5 ms agent step, and an ended
  // episode starts the next one at step 0.
  int episodes_seen = 1;
  for (std::size_t row = 1; row < frames.size() / frame_size; ++row) {
    const double* previous = &frames[(row - 1) * frame_size];
    const double* frame = &frames[row * frame_size];
    if (frame[kViewEpisode] == previous[kViewEpisode]) {
      EXPECT_EQ(frame[kViewStep], previous[kViewStep] + 1);
      EXPECT_NEAR(frame[kViewTime] - previous[kViewTime], 0.005, 1e-9);
    } else {
      EXPECT_EQ(frame[kViewEpisode], previous[kViewEpisode] + 1);
      EXPECT_EQ(frame[kViewStep], 0.0);
      ++episodes_seen;
    }
    EXPECT_NEAR(frame[kViewBaseZ], 0.6, 0.3);
  }
  EXPECT_GT(episodes_seen, 1) << "an untrained policy falls within 200 steps";
  EXPECT_EQ(train.wait(), 0) << train.output();
  EXPECT_NE(train.output().find("final model"), std::string::npos) << train.output();
  std::filesystem::remove_all(run_dir);
}

// Waiting for browsers that never come: Ctrl-C ends the command with an error, at once.
TEST(LiveViewCommand, CtrlCWhileWaitingForBrowsersEndsTheCommand) {
  BackgroundCli rollout({"rollout", "--env", "Upkie-Bullet-Pendulum", "--controller", "zero",
                         "--view", "--view-port", "0", "--view-wait", "1"},
                        "view_wait_interrupted");
  ASSERT_TRUE(rollout.says_it_waits_for_browsers()) << rollout.output();
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(rollout.wait(SIGINT), 1) << rollout.output();
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
  EXPECT_NE(rollout.output().find("interrupted while waiting for 1 browser(s)"), std::string::npos)
      << rollout.output();
}

TEST(LiveViewCommand, TheSpineStreamsEverySimulationStep) {
  const std::string shm_name = "/upkie_rl_view_" + std::to_string(::getpid());
  BackgroundCli spine(
      {"spine", "--shm-name", shm_name, "--nb-substeps", "5", "--view", "--view-port", "0"},
      "view_spine");
  const int port = spine.viewer_port();
  ASSERT_GT(port, 0) << spine.output();
  testing::FrameClient client(port);
  const auto rollout =
      testing::run_cli("rollout --env Upkie-Spine-Pendulum --env-option shm_name=" + shm_name +
                       " --env-option regulate_frequency=false --env-option request_timeout=5"
                       " --controller linear:10,1,0,0.1 --episodes 1 --max-steps 100");
  EXPECT_EQ(rollout.exit_code, 0) << rollout.output;
  const std::size_t frame_size = view_frame_size(kNumServos);
  const std::vector<double> frames = client.read_frames(frame_size, 101);
  ASSERT_GE(frames.size(), 101 * frame_size) << spine.output();
  // The reset, then one frame per agent step of 5 ms; the wheels get velocity targets.
  EXPECT_EQ(frames[kViewStep], 0.0);
  EXPECT_EQ(frames[100 * frame_size + kViewStep], 100.0);
  EXPECT_NEAR(frames[100 * frame_size + kViewTime], 0.5, 1e-9);
  double wheel_command = 0.0;
  for (std::size_t row = 0; row < 101; ++row) {
    wheel_command =
        std::max(wheel_command, std::abs(frames[row * frame_size + kViewFirstAction + 2]));
  }
  EXPECT_GT(wheel_command, 0.0);
  EXPECT_EQ(spine.wait(SIGINT), 0) << spine.output();
}

}  // namespace
}  // namespace upkie_rl
