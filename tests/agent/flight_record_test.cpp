// The flight record of upkie-rl-agent: a record file of `rollout --record` with the runner's
// columns, which `upkie-rl view` and `upkie-rl render` replay, and whose actions are those
// that `upkie-rl rollout --model` computes (its policy controller is a DeployedPolicy of the
// checkpoint) for the recorded observations.

#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "apps/cli_runner.hpp"
#include "common/background_process.hpp"
#include "common/temp_files.hpp"
#include "policy/deployed_policy.hpp"

namespace upkie_rl {
namespace {

using testing::BackgroundProcess;
using testing::run_cli;
using testing::temp_path;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  for (std::string field; std::getline(stream, field, ',');) fields.push_back(field);
  return fields;
}

class AgentRecord : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    record_ = temp_path("agent_flight.csv");
    const std::string shm_name = "/upkie_rl_agent_record" + std::to_string(::getpid());
    BackgroundProcess spine({UPKIE_RL_CLI_PATH, "spine", "--shm-name", shm_name}, "record_spine");
    for (int i = 0; i < 3000 && !std::filesystem::exists("/dev/shm" + shm_name); ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    BackgroundProcess agent({UPKIE_RL_AGENT_PATH, "--model", model_, "--shm-name", shm_name,
                             "--duration", "2", "--record", record_.string()},
                            "record_agent");
    agent_status_ = agent.wait();
    agent_output_ = agent.output();
    spine.wait(SIGINT);
  }

  static inline std::string model_ =
      std::string(UPKIE_RL_TEST_DATA_DIR) + "/policies/pendulum_bullet_seed0.ckpt";
  static inline std::filesystem::path record_;
  static inline int agent_status_ = -1;
  static inline std::string agent_output_;
};

TEST_F(AgentRecord, HasTheRolloutColumnsThenTheRunnersOwn) {
  ASSERT_EQ(agent_status_, 0) << agent_output_;
  std::ifstream in(record_);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("episode,step,t,theta,p,theta_dot,p_dot,action.ground_velocity,reward,"
                         "terminated,truncated,base_x",
                         0),
            0u)
      << header;
  const std::string own =
      ",pitch,ground_position,supervisor_state,loop_period,policy_time,"
      "deadline_miss";
  EXPECT_EQ(header.substr(header.size() - own.size()), own) << header;
  long rows = 0;
  for (std::string line; std::getline(in, line);) {
    ++rows;
    const std::vector<std::string> fields = split(line);
    ASSERT_EQ(fields.size(), split(header).size()) << line;
    EXPECT_EQ(fields[fields.size() - 4], "2") << line;  // running
  }
  EXPECT_GT(rows, 380);
}

TEST_F(AgentRecord, ViewAndRenderReplayIt) {
  ASSERT_EQ(agent_status_, 0) << agent_output_;
  const auto html = temp_path("agent_replay.html");
  const auto view = run_cli("view " + record_.string() + " --html " + html.string());
  EXPECT_EQ(view.exit_code, 0) << view.output;
  EXPECT_NE(view.output.find("1 episode(s)"), std::string::npos) << view.output;
  const auto video = temp_path("agent_replay.mp4");
  const auto render =
      run_cli("render " + record_.string() + " --video-size 160x120 --video " + video.string());
  EXPECT_EQ(render.exit_code, 0) << render.output;
  EXPECT_GT(std::filesystem::file_size(video), 1000u);
}

TEST_F(AgentRecord, ActionsAreThoseOfRolloutsPolicyController) {
  ASSERT_EQ(agent_status_, 0) << agent_output_;
  DeployedPolicy policy = DeployedPolicy::load(model_);
  std::ifstream in(record_);
  std::string line;
  std::getline(in, line);
  std::vector<float> observation(4);
  std::vector<float> action(1);
  long compared = 0;
  while (std::getline(in, line)) {
    const std::vector<std::string> fields = split(line);
    for (std::size_t i = 0; i < 4; ++i) observation[i] = std::stof(fields[3 + i]);
    policy.act(observation, action);
    ASSERT_NEAR(action[0], std::stof(fields[7]), 1e-6) << line;
    ++compared;
  }
  EXPECT_GT(compared, 380);
}

}  // namespace
}  // namespace upkie_rl
