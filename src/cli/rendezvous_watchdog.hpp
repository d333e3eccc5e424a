#pragma once
/// @file
/// Ends the process with a message naming the rendezvous when it does not complete in time.
/// The TCPStore's own timeout does not cover every case: a client that reached a port held
/// by another program, or a rank number used twice, may wait on a socket forever.

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace upkie_rl::apps {

class RendezvousWatchdog {
 public:
  /// Unless cancel() comes within `timeout`, ends the process with `message`
  /// (exit_stuck_process: the stuck threads cannot be unwound).
  RendezvousWatchdog(std::chrono::milliseconds timeout, std::string message);
  ~RendezvousWatchdog();
  RendezvousWatchdog(const RendezvousWatchdog&) = delete;
  RendezvousWatchdog& operator=(const RendezvousWatchdog&) = delete;

  void cancel();

 private:
  std::mutex mutex_;
  std::condition_variable cancelled_changed_;
  bool cancelled_ = false;
  std::thread thread_;
};

}  // namespace upkie_rl::apps
