#include "view/view_server_monitor.hpp"

namespace upkie_rl {

void ViewServerMonitor::client_opened(std::size_t connected) {
  const std::lock_guard lock(mutex_);
  ++statistics_.clients_connected;
  num_clients_ = connected;
  changed_.notify_all();
}

void ViewServerMonitor::client_closed(std::size_t connected) {
  const std::lock_guard lock(mutex_);
  num_clients_ = connected;
  changed_.notify_all();
}

void ViewServerMonitor::http_request() {
  const std::lock_guard lock(mutex_);
  ++statistics_.http_requests;
}

void ViewServerMonitor::frames_collected(std::size_t frames, std::uint64_t skipped) {
  const std::lock_guard lock(mutex_);
  statistics_.frames_skipped += skipped;
  if (frames == 0) return;
  ++statistics_.messages_sent;
  statistics_.frames_sent += frames;
}

void ViewServerMonitor::end_posted(std::size_t audience) {
  const std::lock_guard lock(mutex_);
  end_posted_ = true;
  awaiting_end_ = audience;
  changed_.notify_all();
}

void ViewServerMonitor::end_delivered() {
  const std::lock_guard lock(mutex_);
  if (awaiting_end_ > 0) --awaiting_end_;
  changed_.notify_all();
}

std::size_t ViewServerMonitor::num_clients() const {
  const std::lock_guard lock(mutex_);
  return num_clients_;
}

ViewServerStatistics ViewServerMonitor::statistics() const {
  const std::lock_guard lock(mutex_);
  return statistics_;
}

bool ViewServerMonitor::wait_for_clients(std::size_t count, std::chrono::milliseconds timeout,
                                         const std::atomic<bool>* interrupt) const {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::unique_lock lock(mutex_);
  while (num_clients_ < count) {
    if ((interrupt && interrupt->load()) || std::chrono::steady_clock::now() >= deadline) {
      return false;
    }
    // Short waits: the interrupt flag is set by a signal handler, which cannot notify.
    changed_.wait_for(lock, std::chrono::milliseconds(50));
  }
  return true;
}

void ViewServerMonitor::wait_for_end(std::chrono::milliseconds timeout) const {
  std::unique_lock lock(mutex_);
  changed_.wait_for(lock, timeout, [this] { return end_posted_ && awaiting_end_ == 0; });
}

}  // namespace upkie_rl
