// The flight record of upkie-rl-agent: a record file of `rollout --record` with the runner's
// columns, which `upkie-rl view` and `upkie-rl render` replay; and the actions of the runner
// and of `upkie-rl rollout --model` against the same spine, each recorded with its
// observations, are one function of the checkpoint bit for bit.

#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <string>

#include "agent/agent_spine.hpp"
#include "agent/record_columns.hpp"
#include "apps/cli_runner.hpp"
#include "common/temp_files.hpp"

namespace upkie_rl {
namespace {

using testing::expect_checkpoint_actions;
using testing::kPendulum;
using testing::read_record;
using testing::RecordTable;
using testing::run_cli;
using testing::Spine;
using testing::start_agent;
using testing::temp_path;

class AgentRecord : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    record_ = temp_path("agent_flight.csv");
    Spine spine("record");
    auto agent =
        start_agent(spine, kPendulum, "record", {"--duration", "2", "--record", record_.string()});
    agent_status_ = agent->wait();
    agent_output_ = agent->output();
  }

  static inline std::filesystem::path record_;
  static inline int agent_status_ = -1;
  static inline std::string agent_output_;
};

TEST_F(AgentRecord, HasTheRolloutColumnsThenTheRunnersOwn) {
  ASSERT_EQ(agent_status_, 0) << agent_output_;
  const RecordTable table = read_record(record_.string());
  std::string header;
  for (const std::string& column : table.columns) header += (header.empty() ? "" : ",") + column;
  EXPECT_EQ(header.rfind("episode,step,t,theta,p,theta_dot,p_dot,action.ground_velocity,reward,"
                         "terminated,truncated,base_x",
                         0),
            0u)
      << header;
  const std::string own =
      ",pitch,ground_position,supervisor_state,loop_period,policy_time,"
      "deadline_miss";
  EXPECT_EQ(header.substr(header.size() - own.size()), own) << header;
  for (const auto& row : table.rows) {
    ASSERT_EQ(row.size(), table.columns.size());
    EXPECT_EQ(row[table.column("supervisor_state")], "2");  // running
  }
  // One row per cycle the runner reports (2 s at 200 Hz is 400 on an idle machine; a
  // loaded one misses deadlines and runs fewer).
  const std::string summary = "summary: ";
  const std::size_t at = agent_output_.find(summary);
  ASSERT_NE(at, std::string::npos) << agent_output_;
  const std::size_t cycles = std::stoul(agent_output_.substr(at + summary.size()));
  EXPECT_EQ(table.rows.size(), cycles) << agent_output_;
  EXPECT_GT(cycles, 100u) << agent_output_;
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

TEST_F(AgentRecord, RunnerAndRolloutActAsOneFunctionOfTheCheckpoint) {
  ASSERT_EQ(agent_status_, 0) << agent_output_;
  // `upkie-rl rollout --model` on the same kind of spine, recording what it saw and did.
  const auto rollout_record = temp_path("rollout_on_spine.csv");
  {
    Spine spine("rollout_record");
    const auto rollout =
        run_cli("rollout --env Upkie-Spine-Pendulum --env-option shm_name=" + spine.shm_name() +
                " --model " + kPendulum + " --max-steps 300 --record " + rollout_record.string());
    ASSERT_EQ(rollout.exit_code, 0) << rollout.output;
  }
  const RecordTable runner = read_record(record_.string());
  const RecordTable rollout = read_record(rollout_record.string());
  // Same observation and action columns in both records.
  for (std::size_t i = 0; i <= rollout.column("action.ground_velocity"); ++i) {
    EXPECT_EQ(runner.columns.at(i), rollout.columns.at(i));
  }
  // Each binary's actions are, bit for bit, the checkpoint's DeployedPolicy on its own
  // recorded observations: the same function in both. The runner's rows are its cycles: 2 s
  // at 200 Hz is 400 on an idle machine, and 365 were seen beside four trainings, so they are
  // bounded below as in the test above, not pinned near 400.
  EXPECT_GT(expect_checkpoint_actions(runner, kPendulum), 100u);
  EXPECT_EQ(expect_checkpoint_actions(rollout, kPendulum), 300u);
}

}  // namespace
}  // namespace upkie_rl
