#pragma once
/// @file
/// What a shell command prints (for tests that check files with tools such as ffprobe).

#include <array>
#include <cstdio>
#include <memory>
#include <string>

namespace upkie_rl::testing {

/// Standard output of `command` run by the shell.
inline std::string shell_output(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  std::string output;
  std::array<char, 256> buffer{};
  while (pipe && fgets(buffer.data(), buffer.size(), pipe.get())) output += buffer.data();
  return output;
}

}  // namespace upkie_rl::testing
