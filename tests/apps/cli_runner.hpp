#pragma once
/// @file
/// Runs the command-line tools, `upkie-rl` (UPKIE_RL_CLI_PATH) and `upkie-rl-agent`
/// (UPKIE_RL_AGENT_PATH), and captures what they print.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace upkie_rl::testing {

struct CliResult {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together.

  std::vector<std::string> lines() const {
    std::vector<std::string> result;
    std::istringstream stream(output);
    for (std::string line; std::getline(stream, line);) result.push_back(line);
    return result;
  }
};

/// Runs `program <arguments>` through the shell (arguments are not quoted). With a positive
/// `timeout_seconds`, a run still going after that long is SIGKILLed (exit code 137): a test
/// of a refusal that hangs without its fix fails instead of hanging.
inline CliResult run_program(const std::string& program, const std::string& arguments,
                             int timeout_seconds = 0) {
  const std::string limit =
      timeout_seconds > 0 ? "timeout -s KILL " + std::to_string(timeout_seconds) + " " : "";
  const std::string command = limit + program + " " + arguments + " 2>&1";
  CliResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  std::size_t read = 0;
  while ((read = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
    result.output.append(buffer.data(), read);
  }
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

/// Runs `upkie-rl <arguments>` (UPKIE_RL_CLI_PATH), as run_program.
inline CliResult run_cli(const std::string& arguments, int timeout_seconds = 0) {
  return run_program(UPKIE_RL_CLI_PATH, arguments, timeout_seconds);
}

/// Runs `upkie-rl-agent <arguments>` (UPKIE_RL_AGENT_PATH), as run_program.
inline CliResult run_agent_cli(const std::string& arguments, int timeout_seconds = 0) {
  return run_program(UPKIE_RL_AGENT_PATH, arguments, timeout_seconds);
}

}  // namespace upkie_rl::testing
