#include "cli/child_process.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "cli/command_error.hpp"

extern char** environ;

namespace upkie_rl::apps {

std::filesystem::path this_executable() { return std::filesystem::read_symlink("/proc/self/exe"); }

pid_t spawn_logged(const std::vector<std::string>& arguments, const std::filesystem::path& log) {
  if (arguments.empty()) throw std::invalid_argument("spawn_logged: no command");
  std::vector<char*> argv;
  argv.reserve(arguments.size() + 1);
  for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = 0;
  const int error = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) {
    throw CommandError("cannot start " + arguments[0] + ": " + std::strerror(error));
  }
  return pid;
}

std::optional<ChildExit> wait_for_child() {
  int status = 0;
  const pid_t pid = waitpid(-1, &status, 0);
  if (pid < 0 && errno == EINTR) return std::nullopt;
  if (pid < 0) throw CommandError(std::string("waitpid: ") + std::strerror(errno));
  ChildExit child;
  child.pid = pid;
  child.signalled = WIFSIGNALED(status);
  child.exit_code = child.signalled ? 128 + WTERMSIG(status) : WEXITSTATUS(status);
  return child;
}

std::string last_line(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string last;
  for (std::string line; std::getline(in, line);) {
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  }
  return last;
}

}  // namespace upkie_rl::apps
