#pragma once
/// @file
/// ViewServerMonitor: what the viewer server shares with other threads (its counters, the
/// number of browsers connected, the delivery of the end message), under one mutex. All
/// else of the server lives on its io thread and takes no lock.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>

#include "view/view_server.hpp"

namespace upkie_rl {

class ViewServerMonitor {
 public:
  /// io thread: a browser's WebSocket opened; `connected` are open now.
  void client_opened(std::size_t connected);
  /// io thread: a browser's WebSocket closed; `connected` are open now.
  void client_closed(std::size_t connected);
  /// io thread: an HTTP request came.
  void http_request();
  /// io thread: a client took `frames` frames (in one message when not zero) and missed
  /// `skipped` (it was too slow).
  void frames_collected(std::size_t frames, std::uint64_t skipped);
  /// io thread: the end is posted to the `audience` browsers connected.
  void end_posted(std::size_t audience);
  /// io thread: one of the end's audience had it or went away.
  void end_delivered();

  /// Any thread.
  std::size_t num_clients() const;
  ViewServerStatistics statistics() const;
  /// Any thread: see ViewServer::wait_for_clients.
  bool wait_for_clients(std::size_t count, std::chrono::milliseconds timeout,
                        const std::atomic<bool>* interrupt) const;
  /// Any thread: waits up to `timeout` for the end to be posted and delivered.
  void wait_for_end(std::chrono::milliseconds timeout) const;

 private:
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  ViewServerStatistics statistics_;
  std::size_t num_clients_ = 0;
  bool end_posted_ = false;
  /// Browsers connected when the end was posted that have neither had it nor gone away.
  std::size_t awaiting_end_ = 0;
};

}  // namespace upkie_rl
