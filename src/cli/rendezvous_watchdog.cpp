#include "cli/rendezvous_watchdog.hpp"

#include <utility>

#include "cli/stuck_process_exit.hpp"

namespace upkie_rl::apps {

RendezvousWatchdog::RendezvousWatchdog(std::chrono::milliseconds timeout, std::string message)
    : thread_([this, timeout, message = std::move(message)] {
        std::unique_lock lock(mutex_);
        if (cancelled_changed_.wait_for(lock, timeout, [this] { return cancelled_; })) return;
        exit_stuck_process(message);
      }) {}

RendezvousWatchdog::~RendezvousWatchdog() {
  cancel();
  thread_.join();
}

void RendezvousWatchdog::cancel() {
  const std::lock_guard lock(mutex_);
  cancelled_ = true;
  cancelled_changed_.notify_all();
}

}  // namespace upkie_rl::apps
