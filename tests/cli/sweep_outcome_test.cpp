// The cli layer as a library: a sweep run's outcome file and the child processes a sweep
// launches, without running the upkie-rl tool.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>

#include "cli/child_process.hpp"
#include "cli/command_error.hpp"
#include "cli/sweep_outcome.hpp"
#include "common/temp_files.hpp"

namespace upkie_rl::apps {
namespace {

std::filesystem::path fresh_run_dir(const std::string& name) {
  const std::filesystem::path run_dir = testing::temp_path(name, "upkie_rl_cli_test");
  std::filesystem::remove_all(run_dir);
  std::filesystem::create_directories(run_dir);
  return run_dir;
}

TEST(SweepOutcome, ReadsBackWhatItWroteAndNaNAsNaN) {
  const std::filesystem::path run_dir = fresh_run_dir("round_trip");
  EXPECT_FALSE(read_sweep_outcome(run_dir).has_value()) << "an unfinished run has none";
  SweepOutcome outcome;
  outcome.timesteps = 40960;
  outcome.train_seconds = 12.5;
  outcome.training_mean_return = std::numeric_limits<double>::quiet_NaN();
  outcome.model = "final.ckpt";
  outcome.evaluation.episodes = 10;
  outcome.evaluation.successes = 9;
  outcome.evaluation.mean_return = 280.05;
  outcome.evaluation.std_return = 3.25;
  outcome.evaluation.mean_length = 297.5;
  write_sweep_outcome(run_dir, outcome);
  const std::optional<SweepOutcome> read = read_sweep_outcome(run_dir);
  ASSERT_TRUE(read.has_value());
  EXPECT_EQ(read->timesteps, 40960);
  EXPECT_EQ(read->train_seconds, 12.5);
  EXPECT_TRUE(std::isnan(read->training_mean_return));
  EXPECT_EQ(read->model, "final.ckpt");
  EXPECT_EQ(read->evaluation.episodes, 10);
  EXPECT_EQ(read->evaluation.successes, 9);
  EXPECT_EQ(read->evaluation.mean_return, 280.05);
  EXPECT_EQ(read->evaluation.std_return, 3.25);
  EXPECT_EQ(read->evaluation.mean_length, 297.5);
}

TEST(SweepOutcome, MalformedFileIsACommandErrorNamingIt) {
  const std::filesystem::path run_dir = fresh_run_dir("malformed");
  testing::write_bytes(run_dir / "evaluation.json", "{\"timesteps\": 1}\n");
  try {
    read_sweep_outcome(run_dir);
    FAIL() << "a file without its keys was read";
  } catch (const CommandError& error) {
    EXPECT_NE(std::string(error.what()).find("evaluation.json: malformed"), std::string::npos)
        << error.what();
  }
}

TEST(ChildProcess, LogsOutputAndReportsTheExitCode) {
  const std::filesystem::path log = fresh_run_dir("child") / "child.log";
  const pid_t pid = spawn_logged({"/bin/sh", "-c", "echo first; echo last; echo; exit 3"}, log);
  std::optional<ChildExit> exit;
  while (!(exit = wait_for_child())) {
  }
  EXPECT_EQ(exit->pid, pid);
  EXPECT_EQ(exit->exit_code, 3);
  EXPECT_FALSE(exit->signalled);
  EXPECT_EQ(last_line(log), "last");
  EXPECT_EQ(last_line(log.parent_path() / "no_such.log"), "");
}

}  // namespace
}  // namespace upkie_rl::apps
