// Fault injection (issue 26): every reader of a file handed over by a user or another process
// refuses a device (/dev/zero, which never ends) and a FIFO (which blocks until a writer comes)
// at once, naming the file and what it was meant to be, instead of hanging or filling memory.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "cli/sweep_outcome.hpp"
#include "common/child_call.hpp"
#include "common/temp_files.hpp"
#include "envs/records/record_file.hpp"
#include "onnx/onnx_model_info.hpp"
#include "policy/checkpoint_file.hpp"
#include "rl/logging/scalar_csv_writer.hpp"
#include "rl/logging/tensorboard_writer.hpp"
#include "rl/runs/sweep_plan.hpp"
#include "rl/runs/training_config.hpp"
#include "view/view_session.hpp"

namespace upkie_rl {
namespace {

using testing::child_call_error;

constexpr const char* kNotRegular = ": not a regular file (a FIFO, a device or a socket)";

/// A FIFO at `path`, which no writer ever opens.
std::filesystem::path make_fifo(const std::filesystem::path& path) {
  EXPECT_FALSE(testing::make_fifo(path).empty()) << path;
  return path;
}

std::filesystem::path fifo_path(const std::string& name) {
  return make_fifo(testing::temp_path(name, "upkie_rl_unreadable"));
}

struct Outcome {
  int exit_code = -1;  ///< 137 when `timeout` had to kill it.
  std::string output;
  double seconds = 0.0;
};

/// Runs `upkie-rl <arguments>` (with `environment` before it), killed after 30 s so that a
/// reader that blocks fails the test instead of hanging it.
Outcome run_bounded(const std::string& arguments, const std::string& environment = "") {
  const std::string command = "env " + environment + " timeout -s KILL 30 " +
                              std::string(UPKIE_RL_CLI_PATH) + " " + arguments + " 2>&1";
  const auto start = std::chrono::steady_clock::now();
  Outcome outcome;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return outcome;
  std::array<char, 4096> buffer{};
  for (std::size_t count; (count = fread(buffer.data(), 1, buffer.size(), pipe)) > 0;) {
    outcome.output.append(buffer.data(), count);
  }
  const int status = pclose(pipe);
  outcome.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return outcome;
}

/// `arguments` naming `path` ends with status 1, within 10 s, in at most three lines, one of
/// them "... <what> <path>: not a regular file ...".
void expect_refused(const std::string& arguments, const std::string& what,
                    const std::filesystem::path& path, const std::string& environment = "") {
  const Outcome outcome = run_bounded(arguments, environment);
  EXPECT_EQ(outcome.exit_code, 1) << arguments << "\n" << outcome.output;
  EXPECT_LT(outcome.seconds, 10.0) << arguments;
  EXPECT_NE(outcome.output.find(what + " " + path.string() + kNotRegular), std::string::npos)
      << arguments << "\n"
      << outcome.output;
  EXPECT_LE(std::count(outcome.output.begin(), outcome.output.end(), '\n'), 3) << arguments << "\n"
                                                                               << outcome.output;
}

TEST(UnreadableInput, EveryCommandRefusesADeviceAndAFifoPromptly) {
  const std::filesystem::path fifo = fifo_path("input.fifo");
  const std::string out = testing::temp_path("never", "upkie_rl_unreadable").string();
  for (const std::filesystem::path& path : {std::filesystem::path("/dev/zero"), fifo}) {
    const std::string file = path.string();
    expect_refused("train --quiet --config " + file + " --run-dir " + out, "config file", path);
    expect_refused("sweep --config " + file + " --plan --seeds 0 --output " + out, "config file",
                   path);
    expect_refused("view " + file + " --html " + out + ".html", "record file", path);
    expect_refused("render " + file + " --video " + out + ".gif", "record file", path);
    expect_refused("rollout --env Upkie-Mock-Velocity --max-steps 5 --commands " + file,
                   "velocity commands", path);
    expect_refused("rollout --env Upkie-Bullet-Pendulum --max-steps 5", "robot description", path,
                   "UPKIE_RL_MODEL=" + file);
    expect_refused("info " + file, "checkpoint", path);
  }
  EXPECT_FALSE(std::filesystem::exists(out));
}

/// Each reader of the library, given `path`: what it threw, run in a child killed after 10 s.
std::vector<std::pair<std::string, std::string>> reader_errors(const std::filesystem::path& path) {
  const std::filesystem::path directory = path.parent_path();
  return {
      {"config file", child_call_error([&] { load_training_config(path.string()); })},
      {"record file", child_call_error([&] { read_record_file(path); })},
      {"scalar log", child_call_error([&] { read_scalar_csv(path); })},
      {"event file", child_call_error([&] { read_event_file(path); })},
      {"checkpoint", child_call_error([&] { read_checkpoint_file(path); })},
      {"ONNX model", child_call_error([&] { read_onnx_model_info(path); })},
      {"robot description",
       child_call_error([&] { view_session_json(ViewSession{}, path.string()); })},
  };
}

TEST(UnreadableInput, EveryLibraryReaderRefusesADeviceAndAFifoPromptly) {
  const std::filesystem::path fifo = fifo_path("library.fifo");
  for (const std::filesystem::path& path : {std::filesystem::path("/dev/zero"), fifo}) {
    for (const auto& [what, error] : reader_errors(path)) {
      EXPECT_EQ(error, what + " " + path.string() + kNotRegular);
    }
  }
}

TEST(UnreadableInput, SweepFilesThatAreFifosAreRefusedPromptly) {
  const std::filesystem::path sweep = testing::temp_path("sweep", "upkie_rl_unreadable");
  const std::filesystem::path plan = make_fifo(sweep / "sweep.yaml");
  EXPECT_EQ(child_call_error([&] { load_sweep(sweep); }),
            "sweep file " + plan.string() + kNotRegular);
  const std::filesystem::path outcome = make_fifo(sweep / "run" / "evaluation.json");
  EXPECT_EQ(child_call_error([&] { apps::read_sweep_outcome(outcome.parent_path()); }),
            "sweep outcome " + outcome.string() + kNotRegular);
}

}  // namespace
}  // namespace upkie_rl
