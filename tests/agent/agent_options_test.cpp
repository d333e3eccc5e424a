// upkie-rl-agent's options: every number is finite and in its documented range, every path
// non-empty, and a refused option ends as one line on the standard error naming it, with
// status 1, before the spine is touched (nothing on the standard output, where the runner
// logs).

#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "agent/agent_spine.hpp"
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

TEST(AgentOptions, ARefusedOptionIsOneLineOnStandardError) {
  expect_refused("--open-tries", "0");
  expect_refused("--duration", "-1");
}

}  // namespace
}  // namespace upkie_rl
