#pragma once
/// @file
/// Runs a call in a child process killed after a time limit: a test of a reader given a FIFO
/// (which blocks) or /dev/zero (which never ends) then fails instead of hanging the suite.

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <exception>
#include <functional>
#include <string>
#include <thread>

namespace upkie_rl::testing {

/// What `call` threw (its what()), run in a forked child: "(returned)" if it threw nothing,
/// "(killed after N s)" if it had not ended within `seconds`.
inline std::string child_call_error(const std::function<void()>& call, double seconds = 10.0) {
  int pipe_ends[2];
  if (::pipe(pipe_ends) != 0) return "(no pipe)";
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(pipe_ends[0]);
    std::string message = "(returned)";
    try {
      call();
    } catch (const std::exception& error) {
      message = error.what();
    }
    // A message is far below the pipe's buffer: the write does not wait for the parent.
    [[maybe_unused]] const ssize_t written = ::write(pipe_ends[1], message.data(), message.size());
    ::_exit(0);
  }
  ::close(pipe_ends[1]);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  bool ended = false;
  while (!(ended = ::waitpid(pid, &status, WNOHANG) == pid) &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (!ended) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    ::close(pipe_ends[0]);
    return "(killed after " + std::to_string(seconds) + " s)";
  }
  std::string message;
  char buffer[4096];
  for (ssize_t count; (count = ::read(pipe_ends[0], buffer, sizeof(buffer))) > 0;) {
    message.append(buffer, static_cast<std::size_t>(count));
  }
  ::close(pipe_ends[0]);
  return message;
}

}  // namespace upkie_rl::testing
