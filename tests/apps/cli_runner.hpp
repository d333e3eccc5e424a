#pragma once
/// @file
/// Runs the `upkie-rl` command line (UPKIE_RL_CLI_PATH) and captures what it prints.

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

/// Runs `upkie-rl <arguments>` through the shell (arguments are not quoted). With a
/// positive `timeout_seconds`, a run still going after that long is SIGKILLed (exit code
/// 137): a test of a refusal that hangs without its fix fails instead of hanging.
inline CliResult run_cli(const std::string& arguments, int timeout_seconds = 0) {
  const std::string limit =
      timeout_seconds > 0 ? "timeout -s KILL " + std::to_string(timeout_seconds) + " " : "";
  const std::string command = limit + std::string(UPKIE_RL_CLI_PATH) + " " + arguments + " 2>&1";
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

}  // namespace upkie_rl::testing
