#include "rl/distributed/rank_watchdog.hpp"

#include <sstream>
#include <stdexcept>
#include <utility>

namespace upkie_rl {

namespace {

constexpr const char* kAbortKey = "abort";

std::string heartbeat_key(int rank) { return "beat/" + std::to_string(rank); }

std::vector<std::uint8_t> bytes(const std::string& text) { return {text.begin(), text.end()}; }

}  // namespace

RankWatchdog::RankWatchdog(const DistributedLaunch& launch, c10::intrusive_ptr<c10d::Store> health,
                           RankWatchdogOptions options)
    : launch_(launch), health_(std::move(health)), options_(std::move(options)) {
  if (!options_.on_abandoned) {
    throw std::invalid_argument(
        "RankWatchdog: on_abandoned is required (the application "
        "decides what an abandoned rank does)");
  }
  publish_heartbeat(0);
  thread_ = std::thread([this] { beat(); });
}

RankWatchdog::~RankWatchdog() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

std::string RankWatchdog::who() const {
  return "rank " + std::to_string(launch_.rank) + " of " + std::to_string(launch_.world_size);
}

/// A heartbeat: "<count> <operations entered>".
void RankWatchdog::publish_heartbeat(std::int64_t count) {
  health_->set(heartbeat_key(launch_.rank),
               bytes(std::to_string(count) + " " + std::to_string(operations_.load())));
}

std::vector<RankWatchdog::Heartbeat> RankWatchdog::read_heartbeats() {
  std::vector<Heartbeat> beats(static_cast<std::size_t>(launch_.world_size));
  for (int rank = 0; rank < launch_.world_size; ++rank) {
    if (!health_->check({heartbeat_key(rank)})) continue;
    const std::vector<std::uint8_t> value = health_->get(heartbeat_key(rank));
    std::istringstream text(std::string(value.begin(), value.end()));
    text >> beats[static_cast<std::size_t>(rank)].count >>
        beats[static_cast<std::size_t>(rank)].operations;
  }
  return beats;
}

std::string RankWatchdog::diagnose(std::int64_t entered) {
  const auto window = options_.heartbeat_period * 5 / 2;
  std::vector<Heartbeat> before, after;
  try {
    before = read_heartbeats();
    std::this_thread::sleep_for(window);
    after = read_heartbeats();
  } catch (const std::exception&) {
    return launch_.launcher_store
               ? std::string("the launcher's rendezvous store is unreachable")
               : "rank 0 stopped (the rendezvous store it served at " + launch_.master_addr + ":" +
                     std::to_string(launch_.master_port) + " is gone)";
  }
  std::string faults;
  const std::string seconds = std::to_string(std::chrono::duration<double>(window).count());
  for (int rank = 0; rank < launch_.world_size; ++rank) {
    if (rank == launch_.rank) continue;
    const Heartbeat& first = before[static_cast<std::size_t>(rank)];
    const Heartbeat& second = after[static_cast<std::size_t>(rank)];
    std::string fault;
    if (second.count < 0 || second.count == first.count) {
      fault = "rank " + std::to_string(rank) + " stopped answering (no heartbeat for " +
              seconds.substr(0, seconds.find('.') + 2) +
              " s: it died, was stopped, or its host is unreachable)";
    } else if (second.operations < entered) {
      fault = "rank " + std::to_string(rank) + " is alive but did not reach this operation (" +
              std::to_string(entered - second.operations) + " behind: hung or far slower)";
    }
    if (!fault.empty()) faults += (faults.empty() ? "" : "; ") + fault;
  }
  return faults.empty() ? "every other rank is alive and reached it (a network failure?)" : faults;
}

void RankWatchdog::announce_abort(const std::string& message) {
  try {
    health_->set(kAbortKey, bytes(message));  // For ranks stuck outside the collectives.
  } catch (const std::exception&) {
    // The store is gone too: the others will see that instead.
  }
}

std::string RankWatchdog::abandonment_reason(bool beat_written, bool store_failed) {
  if (beat_written) store_lost_.reset();
  if (store_failed && !store_lost_) store_lost_ = Clock::now();
  if (abort_seen_ && Clock::now() - *abort_seen_ > options_.abort_grace) {
    return "the run was aborted (" + abort_reason_ + ")";
  }
  if (store_lost_ && Clock::now() - *store_lost_ > options_.abort_grace) {
    return launch_.launcher_store
               ? std::string("the launcher's rendezvous store stopped answering")
               : std::string("rank 0 stopped (the rendezvous store it served is gone)");
  }
  return {};
}

/// The heartbeat thread: beats, and tells the application when the run was aborted while
/// this rank is stuck, or when the store is gone.
void RankWatchdog::beat() {
  std::int64_t count = 0;
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stopping_) {
    lock.unlock();
    bool beat_written = false;
    bool store_failed = false;
    try {
      publish_heartbeat(++count);
      beat_written = true;
      if (!abort_seen_ && health_->check({kAbortKey})) {
        const std::vector<std::uint8_t> reason = health_->get(kAbortKey);
        abort_reason_.assign(reason.begin(), reason.end());
        abort_seen_ = Clock::now();
      }
    } catch (const std::exception&) {
      store_failed = true;
    }
    const std::string reason = abandonment_reason(beat_written, store_failed);
    lock.lock();
    if (!reason.empty() && !stopping_) {
      lock.unlock();
      options_.on_abandoned(who() + ": " + reason + "; this rank stops");
      return;
    }
    wake_.wait_for(lock, options_.heartbeat_period, [this] { return stopping_; });
  }
}

}  // namespace upkie_rl
