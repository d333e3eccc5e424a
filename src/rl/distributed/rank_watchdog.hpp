#pragma once
/// @file
/// The watch the ranks of a data-parallel run keep over each other, beside their
/// collectives (rl/distributed/communicator.hpp): each rank's heartbeat in the rendezvous store,
/// the diagnosis of a failed collective from those heartbeats, and the notice that a run was
/// aborted. It decides nothing about the process: when this rank is abandoned (another rank
/// aborted the run, or the store is gone) it tells the application through a callback, and
/// the application decides (upkie-rl train ends the process).

#include <torch/csrc/distributed/c10d/Store.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "rl/distributed/distributed_launch.hpp"

namespace upkie_rl {

/// How often the ranks beat and how long an abandoned rank waits before it is told.
struct RankWatchdogOptions {
  /// Period of the heartbeats (CommunicatorOptions::heartbeat_period).
  std::chrono::milliseconds heartbeat_period{1000};
  /// Grace before `on_abandoned` (CommunicatorOptions::abort_grace).
  std::chrono::milliseconds abort_grace{10'000};
  /// Called once, from the watchdog's thread, with the reason this rank is abandoned.
  std::function<void(const std::string& reason)> on_abandoned;
};

/// One rank's heartbeat thread and its readings of the others'.
class RankWatchdog {
 public:
  /// Writes the first heartbeat through `health` (a store client of its own, with a short
  /// timeout) and starts the thread. Throws what the store throws.
  RankWatchdog(const DistributedLaunch& launch, c10::intrusive_ptr<c10d::Store> health,
               RankWatchdogOptions options);
  ~RankWatchdog();
  RankWatchdog(const RankWatchdog&) = delete;
  RankWatchdog& operator=(const RankWatchdog&) = delete;

  /// Counts a collective this rank enters (heartbeats carry the count); returns it.
  std::int64_t enter_operation() { return ++operations_; }

  /// Names the ranks at fault after the `entered`-th operation failed: two readings of
  /// every heartbeat, 2.5 periods apart (blocks that long).
  std::string diagnose(std::int64_t entered);

  /// Tells the other ranks the run is aborted, with `message` (best effort: a store that is
  /// gone too is what they will see instead).
  void announce_abort(const std::string& message);

 private:
  struct Heartbeat {
    std::int64_t count = -1;  ///< -1: none read.
    std::int64_t operations = 0;
  };

  std::string who() const;
  void publish_heartbeat(std::int64_t count);
  std::vector<Heartbeat> read_heartbeats();
  /// The reason to give this rank up, or empty: called by the thread after each beat
  /// (`beat_written`: the heartbeat reached the store; `store_failed`: a store call threw).
  std::string abandonment_reason(bool beat_written, bool store_failed);
  void beat();

  DistributedLaunch launch_;
  c10::intrusive_ptr<c10d::Store> health_;
  RankWatchdogOptions options_;
  std::atomic<std::int64_t> operations_{0};
  // The thread's view of the run, read and written by it alone.
  using Clock = std::chrono::steady_clock;
  std::optional<Clock::time_point> abort_seen_;
  std::optional<Clock::time_point> store_lost_;
  std::string abort_reason_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace upkie_rl
