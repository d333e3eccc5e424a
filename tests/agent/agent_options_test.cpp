// upkie-rl-agent's options: every number is finite and in its documented range, every path
// non-empty, and a refused option ends as one line on the standard error naming it, with
// status 1, before the spine is touched (nothing on the standard output, where the runner
// logs). A second Ctrl-C while stopping ends the stop commands at once.

#include <gtest/gtest.h>
#include <csignal>

#include <algorithm>
#include <chrono>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "agent/agent_spine.hpp"
#include "common/background_process.hpp"
#include "common/shell_output.hpp"
#include "common/temp_files.hpp"

namespace upkie_rl {
namespace {

using testing::kPendulum;

struct AgentRun {
  int status = -1;
  std::string out;
  std::string err;
};

/// The agent with `args` on a spine that does not exist, standard output and error apart.
AgentRun run_agent(const std::vector<std::string>& args) {
  const auto out = testing::temp_path("agent_options.out");
  const auto err = testing::temp_path("agent_options.err");
  std::string command = std::string(UPKIE_RL_AGENT_PATH) + " --model '" + kPendulum +
                        "' --shm-name /upkie_rl_agent_options_none --open-tries 1";
  for (const std::string& arg : args) command += " '" + arg + "'";
  command += " >" + out.string() + " 2>" + err.string() + "; echo $?";
  AgentRun run;
  run.status = std::stoi(testing::shell_output(command));
  run.out = testing::read_bytes(out);
  run.err = testing::read_bytes(err);
  return run;
}

void expect_refused(const std::string& flag, const std::string& value) {
  const AgentRun run = run_agent({flag, value});
  const std::string what = flag + " '" + value + "'";
  EXPECT_EQ(run.status, 1) << what << "\n" << run.out << run.err;
  EXPECT_EQ(run.out, "") << what;  // nothing logged: the spine was not touched
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << what << "\n" << run.err;
  EXPECT_EQ(run.err.rfind("upkie-rl-agent: error: " + flag, 0), 0) << what << "\n" << run.err;
}

TEST(AgentOptions, NumbersOutsideTheirRangeAreRefusedInOneLine) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--duration", "nan"},
      {"--duration", "inf"},
      {"--duration", "1e308"},
      {"--duration", "-1"},
      {"--max-pitch", "nan"},
      {"--max-pitch", "1e300"},
      {"--max-pitch", "1.6"},  // |pitch| never exceeds pi/2: no limit at all
      {"--max-pitch", "0"},
      {"--max-roll", "nan"},
      {"--max-roll", "3.2"},
      {"--joint-position-margin", "nan"},
      {"--joint-position-margin", "-1e9"},
      {"--joint-velocity-factor", "inf"},
      {"--joint-velocity-factor", "-1"},
      {"--velocity-command-rate", "nan"},
      {"--velocity-command-rate", "-1"},
      {"--position-command-rate", "inf"},
      {"--max-torque", "nan"},
      {"--max-torque", "-1"},
      {"--max-torque", "1e300"},
      {"--spine-timeout", "nan"},
      {"--spine-timeout", "0"},
      {"--spine-timeout", "1e12"},
      {"--max-deadline-misses", "0"},
      {"--max-deadline-misses", "1000000"},
      {"--max-cycle-periods", "nan"},
      {"--max-cycle-periods", "0"},
      {"--stop-cycles", "-1"},
      {"--stop-cycles", "2000000000"},
      {"--open-tries", "0"},
  };
  for (const auto& [flag, value] : cases) expect_refused(flag, value);
}

TEST(AgentOptions, EmptyPathsAreRefused) {
  expect_refused("--record", "");
  expect_refused("--commands", "");
  expect_refused("--model", "");
}

TEST(AgentOptions, MalformedSharedMemoryNamesAreRefused) {
  expect_refused("--shm-name", "");
  expect_refused("--shm-name", "noslash");
  expect_refused("--shm-name", "/a/b");
  expect_refused("--shm-name", "/" + std::string(300, 'x'));
}

TEST(AgentOptions, HelpShowsTheRanges) {
  const AgentRun run = run_agent({"--help"});
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("--max-pitch"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("NUMBER in [0.01, 1.5]"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("NUMBER in [0, 200]"), std::string::npos) << run.out;
}

TEST(AgentOptions, TheRangesBoundsAreAccepted) {
  // Accepted options go on to the spine, which is not there: the runner's own refusal.
  const AgentRun run = run_agent({"--max-pitch", "1.5", "--stop-cycles", "200", "--duration",
                                  "604800", "--max-torque", "0", "--spine-timeout", "10"});
  EXPECT_EQ(run.status, 2) << run.out << run.err;
  EXPECT_NE(run.out.find("no spine to stop"), std::string::npos) << run.out;
}

TEST(AgentOptions, SecondInterruptCutsStoppingShort) {
  // 200 stop cycles take 1 s at 200 Hz; an operator's Ctrl-C during them ends them at once.
  testing::Spine spine("cut_short");
  auto agent = testing::start_agent(spine, kPendulum, "cut_short",
                                    {"--duration", "1", "--stop-cycles", "200"});
  bool stopping = false;
  for (int i = 0; i < 2000 && !stopping; ++i) {
    stopping = agent->output().find("running -> stopping") != std::string::npos;
    if (!stopping) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(stopping) << agent->output();
  EXPECT_EQ(agent->wait(SIGINT), 3) << agent->output();
  const std::string output = agent->output();
  const std::string cut_short = " of 200 stop cycles answered (cut short by SIGINT or SIGTERM)";
  const auto at = output.find(cut_short);
  ASSERT_NE(at, std::string::npos) << output;
  const auto number_at = output.rfind(' ', at - 1) + 1;
  EXPECT_LT(std::stoi(output.substr(number_at, at - number_at)), 150) << output;
  EXPECT_NE(output.find("upkie-rl-agent: stopping cut short by a second interrupt after"),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("Stop request sent"), std::string::npos) << output;
}

TEST(AgentOptions, InterruptEndsTheWaitForTheSpine) {
  // 30 attempts 1 s apart at a spine that is not there: Ctrl-C must not wait them out.
  testing::BackgroundProcess agent({UPKIE_RL_AGENT_PATH, "--model", kPendulum, "--shm-name",
                                    "/upkie_rl_agent_options_absent", "--open-tries", "30"},
                                   "agent_open_interrupt");
  bool waiting = false;
  for (int i = 0; i < 2000 && !waiting; ++i) {
    waiting = agent.output().find("waiting for spine") != std::string::npos;
    if (!waiting) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(waiting) << agent.output();
  const auto signalled = std::chrono::steady_clock::now();
  EXPECT_EQ(agent.wait(SIGINT), 2) << agent.output();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count();
  EXPECT_LT(seconds, 5.0) << agent.output();  // the remaining attempts would take 28 s
  EXPECT_NE(agent.output().find("interrupted while waiting for spine"), std::string::npos)
      << agent.output();
}

}  // namespace
}  // namespace upkie_rl
