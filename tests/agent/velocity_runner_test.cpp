// upkie-rl-agent with a velocity policy (Upkie-*-Velocity) against `upkie-rl spine`: the
// commands of a file (`rollout --commands`'s format), of lines on the standard input and of
// keys reach the policy's observation, clamped to the trained ranges; without an input the
// robot is told to stand still. The policy is a short training made here (the robot it
// drives falls within about a second: these tests check the commands and the stop path,
// not the balance).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "agent/agent_spine.hpp"
#include "agent/record_columns.hpp"
#include "apps/cli_runner.hpp"
#include "common/temp_files.hpp"
#include "envs/tasks/velocity_command_limiter.hpp"
#include "envs/tasks/velocity_command_schedule.hpp"
#include "policy/deployed_policy.hpp"

namespace upkie_rl {
namespace {

using testing::BackgroundProcess;
using testing::expect_checkpoint_actions;
using testing::read_record;
using testing::RecordTable;
using testing::Spine;
using testing::start_agent;
using testing::temp_path;

constexpr double kFrequency = 50.0;  // [Hz] of the velocity task

/// The checkpoint of one PPO iteration of velocity.yaml with `settings` (more --set pairs),
/// trained in a fresh run directory named for `tag` (about 10 s on a loaded 2-core machine).
std::string train_tiny_velocity_policy(const std::string& tag,
                                       const std::vector<std::string>& settings) {
  const auto run_dir = temp_path("agent_" + tag + "_run");
  std::filesystem::remove_all(run_dir);
  const std::string configs = std::string(UPKIE_RL_TEST_DATA_DIR) + "/../../configs/";
  std::vector<std::string> args = {UPKIE_RL_CLI_PATH, "train", "--config",
                                   configs + "velocity.yaml"};
  for (const std::string& setting :
       {"ppo.total_timesteps=1024", "ppo.n_steps=1024", "ppo.batch_size=512", "env.num_envs=2",
        "env.mix_envs=1", "env.threads=1"}) {
    args.insert(args.end(), {"--set", setting});
  }
  for (const std::string& setting : settings) args.insert(args.end(), {"--set", setting});
  args.insert(args.end(), {"--run-dir", run_dir.string()});
  BackgroundProcess train(args, "agent_" + tag + "_train");
  EXPECT_EQ(train.wait(), 0) << train.output();
  std::string model;
  for (const auto& entry : std::filesystem::directory_iterator(run_dir)) {
    if (entry.path().extension() == ".ckpt") model = entry.path().string();
  }
  EXPECT_FALSE(model.empty()) << train.output();
  return model;
}

/// Runs the agent with `model` for `duration` s on a MuJoCo spine with `extra` options,
/// through `sh -c` when `feed` (a shell command whose output becomes the agent's standard
/// input) is given, checks that it ran the velocity task and detached, and returns its output.
std::string run_velocity_agent(const std::string& model, const std::string& tag,
                               const std::string& duration, std::vector<std::string> extra,
                               const std::string& feed = "") {
  Spine spine(tag, {}, "mujoco");
  std::vector<std::string> args = {"--duration", duration, "--max-pitch", "1.2"};
  args.insert(args.end(), extra.begin(), extra.end());
  std::unique_ptr<BackgroundProcess> agent;
  if (feed.empty()) {
    agent = start_agent(spine, model, tag, args);
  } else {
    std::string command = "(" + feed + ") | " + UPKIE_RL_AGENT_PATH + " --model " + model +
                          " --shm-name " + spine.shm_name();
    for (const std::string& arg : args) command += " " + arg;
    agent = std::make_unique<BackgroundProcess>(std::vector<std::string>{"sh", "-c", command}, tag);
  }
  const int status = agent->wait();
  const std::string output = agent->output();
  EXPECT_TRUE(status == 0 || status == 2) << output;  // 2: the supervisor stopped a fall
  EXPECT_NE(output.find("on Upkie-Spine-Velocity at 50 Hz"), std::string::npos) << output;
  EXPECT_NE(output.find("stopping -> stopped: detached"), std::string::npos) << output;
  return output;
}

/// A standing velocity policy (velocity.yaml's task).
class VelocityRunner : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { model_ = train_tiny_velocity_policy("velocity", {}); }

  static std::string run_agent(const std::string& tag, std::vector<std::string> extra,
                               const std::string& feed = "") {
    return run_velocity_agent(model_, "velocity_" + tag, "3", std::move(extra), feed);
  }

  static inline std::string model_;
};

/// The command columns of each row of `record`.
std::vector<VelocityCommand> recorded_commands(const RecordTable& record) {
  const std::size_t forward = record.column("command.forward_velocity");
  const std::size_t yaw = record.column("command.yaw_rate");
  EXPECT_LT(yaw, record.columns.size());
  std::vector<VelocityCommand> commands;
  for (const auto& row : record.rows) {
    commands.push_back({std::stod(row.at(forward)), std::stod(row.at(yaw))});
  }
  return commands;
}

bool same_float(double recorded, double expected) {
  return static_cast<float>(recorded) == static_cast<float>(expected);
}

TEST_F(VelocityRunner, FileCommandsHoldFromTheirTimeAsInRolloutAndTheRecordReplays) {
  const auto commands = temp_path("agent_velocity_commands.csv");
  testing::write_bytes(commands, "time,vx,wz\n0,0,0\n0.1,0.3,0\n0.2,0.3,-0.5\n0.3,5,0\n");
  const auto record = temp_path("agent_velocity_file.csv");
  const std::string output =
      run_agent("file", {"--commands", commands.string(), "--record", record.string()});
  EXPECT_NE(output.find("from file " + commands.string() +
                        ": forward velocity 0.3 m/s, yaw rate "
                        "-0.5 rad/s"),
            std::string::npos)
      << output;
  // velocity.yaml keeps the default range of forward velocity commands, +-1 m/s.
  EXPECT_NE(output.find("(5 m/s, 0 rad/s) clamped to the trained ranges +-1 m/s"),
            std::string::npos)
      << output;
  const VelocityCommandSchedule schedule(
      {{0.0, {0.0, 0.0}}, {0.1, {0.3, 0.0}}, {0.2, {0.3, -0.5}}, {0.3, {1.0, 0.0}}});
  const RecordTable table = read_record(record.string());
  const std::vector<VelocityCommand> seen = recorded_commands(table);
  ASSERT_GT(seen.size(), 20u) << output;  // past the last row's time (0.3 s: 15 cycles)
  const std::size_t step = table.column("step");
  // Row k holds the observation of cycle k, which shows the command at k / frequency: the
  // rows are targets, followed within velocity.yaml's acceleration limits (the defaults:
  // 1 m/s² forward, yaw steps) from 0 at reset, as in rollout.
  VelocityCommandLimiter limiter(1.0, 0.0);
  limiter.start(schedule.at(0.0));
  int cycle = 0;
  for (std::size_t row = 0; row < seen.size(); ++row) {
    const int row_cycle = std::stoi(table.rows[row].at(step));
    for (; cycle < row_cycle; ++cycle) {
      limiter.advance(schedule.at((cycle + 1) / kFrequency), 1.0 / kFrequency);
    }
    const VelocityCommand& wanted = limiter.command();
    EXPECT_TRUE(same_float(seen[row].forward_velocity, wanted.forward_velocity) &&
                same_float(seen[row].yaw_rate, wanted.yaw_rate))
        << "row " << row << ": " << seen[row].forward_velocity << " against "
        << wanted.forward_velocity;
  }
  EXPECT_GT(expect_checkpoint_actions(table, model_), 20u);
  const auto html = temp_path("agent_velocity_replay.html");
  const auto view = testing::run_cli("view " + record.string() + " --html " + html.string());
  EXPECT_EQ(view.exit_code, 0) << view.output;
  EXPECT_NE(view.output.find("1 episode(s), " + std::to_string(seen.size()) + " steps"),
            std::string::npos)
      << view.output;
  const auto video = temp_path("agent_velocity_replay.mp4");
  const auto render = testing::run_cli("render " + record.string() +
                                       " --video-size 160x120 --video " + video.string());
  EXPECT_EQ(render.exit_code, 0) << render.output;
  EXPECT_GT(std::filesystem::file_size(video), 1000u);
}

TEST_F(VelocityRunner, StandardInputLinesTakeEffectWhenRead) {
  const auto record = temp_path("agent_velocity_stdin.csv");
  const std::string output =
      run_agent("stdin", {"--commands", "-", "--record", record.string()},
                "echo 0.25,0; echo not a command; sleep 0.5; echo 0.25,-0.5; sleep 3");
  EXPECT_NE(output.find("from standard input: forward velocity 0.25 m/s, yaw rate 0 rad/s"),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("ignored the line 'not a command'"), std::string::npos) << output;
  const std::vector<VelocityCommand> seen = recorded_commands(read_record(record.string()));
  ASSERT_FALSE(seen.empty()) << output;
  bool first_seen = false;
  bool second_seen = false;
  for (const VelocityCommand& command : seen) {
    first_seen |= same_float(command.forward_velocity, 0.25) && command.yaw_rate == 0.0;
    second_seen |= same_float(command.forward_velocity, 0.25) && same_float(command.yaw_rate, -0.5);
  }
  EXPECT_TRUE(first_seen) << output;
  // The robot falls about a second after the start: the second line, 0.5 s later, comes
  // before, unless the machine is loaded enough to start the agent late.
  if (output.find("yaw rate -0.5 rad/s") != std::string::npos) EXPECT_TRUE(second_seen) << output;
}

TEST_F(VelocityRunner, KeysStepTheCommand) {
  const std::string output = run_agent("keyboard", {"--keyboard"}, "printf 'wwd'; sleep 3");
  EXPECT_NE(output.find("from keyboard: forward velocity 0.2 m/s, yaw rate -0.25 rad/s"),
            std::string::npos)
      << output;
}

TEST_F(VelocityRunner, WithoutAnInputTheRobotIsToldToStandStill) {
  const auto record = temp_path("agent_velocity_still.csv");
  const std::string output = run_agent("still", {"--record", record.string()});
  EXPECT_NE(output.find("from no input (stand still): forward velocity 0 m/s, yaw rate 0 rad/s"),
            std::string::npos)
      << output;
  const std::vector<VelocityCommand> seen = recorded_commands(read_record(record.string()));
  ASSERT_FALSE(seen.empty()) << output;
  for (const VelocityCommand& command : seen) {  // never the training's random commands
    EXPECT_EQ(command.forward_velocity, 0.0);
    EXPECT_EQ(command.yaw_rate, 0.0);
  }
}

TEST(VelocityRunnerOptions, CommandsNeedAVelocityPolicy) {
  auto agent = std::make_unique<BackgroundProcess>(
      std::vector<std::string>{UPKIE_RL_AGENT_PATH, "--model", testing::kPendulum, "--shm-name",
                               "/upkie_rl_agent_no_spine", "--commands", "-", "--open-tries", "1"},
      "velocity_refused");
  EXPECT_EQ(agent->wait(), 2);
  const std::string output = agent->output();
  EXPECT_NE(output.find("--commands and --keyboard need a velocity policy (Upkie-*-Velocity); "),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("was trained on Upkie-Bullet-Pendulum"), std::string::npos) << output;
}

/// A velocity policy with the body-height command (a short training made here, as above).
class HeightRunner : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    model_ = train_tiny_velocity_policy(
        "height", {"env.options.height_command=true", "env.options.leg_action_scale=1"});
  }

  /// The agent reads its standard input, which stays open 3 s without a `feed`.
  static std::string run_agent(const std::string& tag, std::vector<std::string> extra,
                               const std::string& feed = "") {
    return run_velocity_agent(model_, "height_" + tag, "2", std::move(extra),
                              feed.empty() ? "sleep 3" : feed);
  }

  static inline std::string model_;
};

TEST_F(HeightRunner, FileHeightsAreClampedToTheTrainedRangeAndObserved) {
  const auto commands = temp_path("agent_height_commands.csv");
  testing::write_bytes(commands, "time,vx,wz,height\n0,0,0,0.55\n0.1,0,0,0.37\n");
  const auto record = temp_path("agent_height_file.csv");
  const std::string output =
      run_agent("file", {"--commands", commands.string(), "--record", record.string()});
  EXPECT_NE(output.find("forward velocity 0 m/s, yaw rate 0 rad/s, height 0.55 m"),
            std::string::npos)
      << output;
  // 0.37 m is a height the task accepts (a file is refused below 0.36 m) but below the
  // trained range's 0.53 m.
  EXPECT_NE(output.find("(0 m/s, 0 rad/s, 0.37 m) clamped to the trained ranges"),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("height 0.53 m"), std::string::npos) << output;
  const RecordTable table = read_record(record.string());
  const std::size_t height = table.column("command.height");
  ASSERT_LT(height, table.columns.size());
  ASSERT_GT(table.rows.size(), 10u) << output;
  // The followed height ramps down from standing at 0.1 m/s toward the clamped target.
  double previous = 1.0;
  for (const auto& row : table.rows) {
    const double value = std::stod(row.at(height));
    EXPECT_LE(value, previous + 1e-6);
    EXPECT_GE(value, 0.53 - 1e-6);
    previous = value;
  }
  EXPECT_LT(previous, 0.557 - 0.005) << "the height came down";
}

TEST_F(HeightRunner, StandardInputAndKeysCarryAHeight) {
  const std::string lines = run_agent("stdin", {"--commands", "-"}, "echo 0.1,0,0.54; sleep 3");
  EXPECT_NE(lines.find("from standard input: forward velocity 0.1 m/s, yaw rate 0 rad/s, height "
                       "0.54 m"),
            std::string::npos)
      << lines;
  // Two steps down ask 0.517 m: clamped to the trained range's 0.53 m.
  const std::string keys = run_agent("keyboard", {"--keyboard"}, "printf 'ff'; sleep 3");
  EXPECT_NE(keys.find("(0 m/s, 0 rad/s, 0.517 m) clamped to the trained ranges"), std::string::npos)
      << keys;
  EXPECT_NE(keys.find("from keyboard: forward velocity 0 m/s, yaw rate 0 rad/s, height 0.53 m"),
            std::string::npos)
      << keys;
}

/// A velocity policy that sees the last two observations (env option observation_history;
/// a short training made here, as above).
class HistoryRunner : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    model_ = train_tiny_velocity_policy("history", {"env.options.observation_history=2"});
  }

  static inline std::string model_;
};

/// Checks that the rows of `record` show, after "t", the observation then the previous one
/// (the history of the checkpoint's environment) and that its actions are the checkpoint's;
/// returns the rows where the previous row was the step before in the same episode.
std::size_t expect_history_rows(const RecordTable& record, const std::string& model) {
  const std::size_t first = record.column("t") + 1;
  const std::size_t previous = record.column("gyro.y@t-1");
  const std::size_t current = record.column("gyro.y");
  EXPECT_LT(previous, record.columns.size());
  EXPECT_EQ(current, first + 10);  // VelocityTask's observation, newest first
  if (previous >= record.columns.size()) return 0;
  const std::size_t size = previous - current;  // one observation
  EXPECT_EQ(record.columns.at(first + size), record.columns.at(first) + "@t-1");
  std::size_t consecutive = 0;
  for (std::size_t row = 1; row < record.rows.size(); ++row) {
    const auto& now = record.rows[row];
    const auto& before = record.rows[row - 1];
    if (now.at(0) != before.at(0) || std::stoi(now.at(1)) != std::stoi(before.at(1)) + 1) continue;
    for (std::size_t i = 0; i < size; ++i) {
      EXPECT_EQ(now.at(first + size + i), before.at(first + i)) << "row " << row << ", " << i;
    }
    ++consecutive;
  }
  EXPECT_EQ(expect_checkpoint_actions(record, model), record.rows.size());
  return consecutive;
}

TEST_F(HistoryRunner, RolloutTheSpineEnvAndTheRunnerFeedTheHistoryTheCheckpointWants) {
  const DeployedPolicy policy = DeployedPolicy::load(model_);
  // 2 x the 23 of configs/velocity.yaml: height_command=false (20), observe_acceleration (3).
  EXPECT_EQ(policy.observation_space().size(), 46u);
  // `upkie-rl rollout` on the training's engine, then on a MuJoCo spine: the checkpoint's
  // observation_history comes with its task options, as the runner's does.
  const auto mujoco_record = temp_path("history_rollout_mujoco.csv");
  const auto on_mujoco = testing::run_cli("rollout --env Upkie-MuJoCo-Velocity --model " + model_ +
                                          " --max-steps 30 --record " + mujoco_record.string());
  ASSERT_EQ(on_mujoco.exit_code, 0) << on_mujoco.output;
  EXPECT_GT(expect_history_rows(read_record(mujoco_record.string()), model_), 20u);
  const auto spine_record = temp_path("history_rollout_spine.csv");
  {
    Spine spine("history_rollout", {}, "mujoco");
    const auto on_spine = testing::run_cli(
        "rollout --env Upkie-Spine-Velocity --env-option shm_name=" + spine.shm_name() +
        " --model " + model_ + " --max-steps 30 --record " + spine_record.string());
    ASSERT_EQ(on_spine.exit_code, 0) << on_spine.output;
  }
  EXPECT_GT(expect_history_rows(read_record(spine_record.string()), model_), 20u);
  // upkie-rl-agent on the spine.
  const auto agent_record = temp_path("history_agent.csv");
  run_velocity_agent(model_, "history_agent", "2", {"--record", agent_record.string()});
  EXPECT_GT(expect_history_rows(read_record(agent_record.string()), model_), 20u);
  // The ONNX export takes the whole history as its input.
  const auto onnx = temp_path("history.onnx");
  const auto exported = testing::run_cli("export " + model_ + " --onnx " + onnx.string());
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  const auto info = testing::run_cli("info " + onnx.string());
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_NE(info.output.find("input: observation FLOAT [batch, 46]"), std::string::npos)
      << info.output;
}

}  // namespace
}  // namespace upkie_rl
