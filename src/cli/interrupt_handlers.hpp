#pragma once
/// @file
/// Ctrl-C and SIGTERM as a flag: commands that serve until interrupted (spine, view) stop
/// cleanly, releasing what they hold, instead of being killed.

#include <atomic>
#include <csignal>

namespace upkie_rl::apps {

/// Set by SIGINT/SIGTERM while an InterruptHandlers lives. A signal handler can only reach
/// a static; this one is written by the handler and read by the serving loop, nothing else.
extern std::atomic<bool> interrupt_requested;

/// Installs the SIGINT/SIGTERM handlers for the lifetime of the object (clearing
/// interrupt_requested), then restores the previous ones.
class InterruptHandlers {
 public:
  InterruptHandlers();
  ~InterruptHandlers();
  InterruptHandlers(const InterruptHandlers&) = delete;
  InterruptHandlers& operator=(const InterruptHandlers&) = delete;

 private:
  struct sigaction previous_int_ {};
  struct sigaction previous_term_ {};
};

}  // namespace upkie_rl::apps
