#pragma once
/// @file
/// Child processes of the command line (the runs a sweep launches locally), each writing
/// what it prints to its own log file.

#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace upkie_rl::apps {

/// The path of the running executable (/proc/self/exe), to launch its own subcommands.
std::filesystem::path this_executable();

/// Starts `arguments` (arguments[0]: the executable's path) with stdout and stderr appended
/// to `log`. Throws std::runtime_error naming the command when it cannot start.
pid_t spawn_logged(const std::vector<std::string>& arguments, const std::filesystem::path& log);

/// A child that ended.
struct ChildExit {
  pid_t pid = 0;
  int exit_code = 0;  ///< Its exit code, or 128 + the signal that killed it.
  bool signalled = false;
};

/// Waits for any child to end; nothing when a signal interrupted the wait (the caller checks
/// why, then waits again).
std::optional<ChildExit> wait_for_child();

/// The last non-empty line of a text file (a failed run's error), "" if none.
std::string last_line(const std::filesystem::path& path);

}  // namespace upkie_rl::apps
