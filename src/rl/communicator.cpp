#include "rl/communicator.hpp"

#include <torch/csrc/distributed/c10d/PrefixStore.hpp>
#include <torch/csrc/distributed/c10d/ProcessGroupGloo.hpp>
#include <torch/csrc/distributed/c10d/TCPStore.hpp>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace upkie_rl {

namespace {

class GlooCommunicator final : public Communicator {
 public:
  GlooCommunicator(const DistributedLaunch& launch, const CommunicatorOptions& options)
      : launch_(launch), options_(options) {
    const std::chrono::milliseconds timeout = options.timeout;
    c10d::TCPStoreOptions store_options;
    store_options.port = static_cast<std::uint16_t>(launch.master_port);
    store_options.isServer = launch.rank == 0 && !launch.launcher_store;
    store_options.numWorkers = launch.world_size;
    store_options.waitWorkers = true;
    store_options.timeout = timeout;
    const std::string where = launch.master_addr + ":" + std::to_string(launch.master_port);
    try {
      store_ = c10::make_intrusive<c10d::TCPStore>(launch.master_addr, store_options);
    } catch (const std::exception& error) {
      throw DistributedError(who() + ": the rendezvous at " + where +
                             " failed: " + first_line(error));
    }
    auto gloo_options = c10d::ProcessGroupGloo::Options::create(timeout);
    // Loopback worlds talk over 127.0.0.1; others over the interface the host name
    // resolves to (GLOO_SOCKET_IFNAME is not read here).
    const bool loopback = launch.master_addr == "127.0.0.1" || launch.master_addr == "localhost";
    gloo_options->devices.push_back(
        loopback ? c10d::ProcessGroupGloo::createDeviceForHostname("127.0.0.1")
                 : c10d::ProcessGroupGloo::createDefaultDevice());
    gloo_options->threads = 1;
    try {
      // Our keys apart from the launcher's, in a store it may share.
      const auto keys = c10::make_intrusive<c10d::PrefixStore>("upkie_rl", store_);
      group_ = c10::make_intrusive<c10d::ProcessGroupGloo>(keys, launch.rank, launch.world_size,
                                                           gloo_options);
    } catch (const std::exception& error) {
      throw DistributedError(who() +
                             ": the Gloo process group failed to connect: " + first_line(error));
    }
    // Heartbeats go through a client of their own, with a short timeout, so that a store
    // that stopped answering cannot hold a diagnosis for the whole operation timeout.
    try {
      c10d::TCPStoreOptions health_options;
      health_options.port = store_options.port;
      health_options.isServer = false;
      health_options.waitWorkers = false;
      health_options.timeout = std::min(timeout, std::chrono::milliseconds(5000));
      health_ = c10::make_intrusive<c10d::PrefixStore>(
          "upkie_rl/health",
          c10::make_intrusive<c10d::TCPStore>(launch.master_addr, health_options));
      publish_heartbeat(0);
    } catch (const std::exception& error) {
      throw DistributedError(who() + ": cannot write heartbeats to the store at " + where + ": " +
                             first_line(error));
    }
    heartbeat_ = std::thread([this] { beat(); });
  }

  ~GlooCommunicator() override {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    heartbeat_.join();
  }
  GlooCommunicator(const GlooCommunicator&) = delete;
  GlooCommunicator& operator=(const GlooCommunicator&) = delete;

  int rank() const override { return launch_.rank; }
  int world_size() const override { return launch_.world_size; }

  void sum(torch::Tensor values) override {
    std::vector<torch::Tensor> tensors = {values};
    run("sum", [&] { return group_->allreduce(tensors); });
  }

  void broadcast(torch::Tensor values, int root) override {
    std::vector<torch::Tensor> tensors = {values};
    c10d::BroadcastOptions options;
    options.rootRank = root;
    run("broadcast", [&] { return group_->broadcast(tensors, options); });
  }

 private:
  std::string who() const {
    return "rank " + std::to_string(launch_.rank) + " of " + std::to_string(launch_.world_size);
  }

  static std::string first_line(const std::exception& error) {
    const std::string message = error.what();
    return message.substr(0, message.find('\n'));
  }

  template <typename Start>
  void run(const char* operation, const Start& start) {
    const std::int64_t entered = ++operations_;
    try {
      start()->wait();
    } catch (const std::exception& error) {
      const std::string message = who() + ": " + operation + " failed: " + diagnose(entered) +
                                  " (" + first_line(error) + ")";
      try {
        health_->set(kAbortKey, bytes(message));  // for ranks stuck outside the collectives
      } catch (const std::exception&) {
        // The store is gone too: the others will see that instead.
      }
      throw DistributedError(message);
    }
  }

  static constexpr const char* kAbortKey = "abort";

  static std::string heartbeat_key(int rank) { return "beat/" + std::to_string(rank); }

  static std::vector<std::uint8_t> bytes(const std::string& text) {
    return {text.begin(), text.end()};
  }

  /// A heartbeat: "<count> <operations entered>".
  void publish_heartbeat(std::int64_t count) {
    health_->set(heartbeat_key(launch_.rank),
                 bytes(std::to_string(count) + " " + std::to_string(operations_.load())));
  }

  struct Heartbeat {
    std::int64_t count = -1;  ///< -1: none read.
    std::int64_t operations = 0;
  };

  std::vector<Heartbeat> read_heartbeats() {
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

  /// Names the ranks at fault after an operation failed: two readings of every heartbeat,
  /// 2.5 periods apart.
  std::string diagnose(std::int64_t entered) {
    const auto window = options_.heartbeat_period * 5 / 2;
    std::vector<Heartbeat> before, after;
    try {
      before = read_heartbeats();
      std::this_thread::sleep_for(window);
      after = read_heartbeats();
    } catch (const std::exception&) {
      return launch_.launcher_store
                 ? std::string("the launcher's rendezvous store is unreachable")
                 : "rank 0 stopped (the rendezvous store it served at " + launch_.master_addr +
                       ":" + std::to_string(launch_.master_port) + " is gone)";
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
    return faults.empty() ? "every other rank is alive and reached it (a network failure?)"
                          : faults;
  }

  /// The heartbeat thread: beats, and gives the process up when the run was aborted while
  /// it is stuck, or when the store is gone.
  void beat() {
    using Clock = std::chrono::steady_clock;
    std::optional<Clock::time_point> abort_seen, store_lost;
    std::string abort_reason;
    std::int64_t count = 0;
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stopping_) {
      lock.unlock();
      try {
        publish_heartbeat(++count);
        store_lost.reset();
        if (!abort_seen && health_->check({kAbortKey})) {
          const std::vector<std::uint8_t> reason = health_->get(kAbortKey);
          abort_reason.assign(reason.begin(), reason.end());
          abort_seen = Clock::now();
        }
      } catch (const std::exception&) {
        if (!store_lost) store_lost = Clock::now();
      }
      std::string reason;
      if (abort_seen && Clock::now() - *abort_seen > options_.abort_grace) {
        reason = "the run was aborted (" + abort_reason + ")";
      } else if (store_lost && Clock::now() - *store_lost > options_.abort_grace) {
        reason = launch_.launcher_store
                     ? std::string("the launcher's rendezvous store stopped answering")
                     : std::string("rank 0 stopped (the rendezvous store it served is gone)");
      }
      lock.lock();
      if (!reason.empty() && !stopping_) {
        lock.unlock();
        abandon(who() + ": " + reason + "; this rank stops");
        return;
      }
      wake_.wait_for(lock, options_.heartbeat_period, [this] { return stopping_; });
    }
  }

  void abandon(const std::string& reason) {
    if (options_.on_abandoned) {
      options_.on_abandoned(reason);
      return;
    }
    std::fprintf(stderr, "upkie-rl: error: %s\n", reason.c_str());
    std::fflush(stderr);
    std::_Exit(1);
  }

  DistributedLaunch launch_;
  CommunicatorOptions options_;
  c10::intrusive_ptr<c10d::Store> store_;
  c10::intrusive_ptr<c10d::Store> health_;
  c10::intrusive_ptr<c10d::ProcessGroupGloo> group_;
  std::atomic<std::int64_t> operations_{0};
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::thread heartbeat_;
};

}  // namespace

std::unique_ptr<Communicator> connect_communicator(const DistributedLaunch& launch,
                                                   const CommunicatorOptions& options) {
  if (!launch.distributed()) return std::make_unique<SoloCommunicator>();
  // Gloo's transport writes to its sockets without MSG_NOSIGNAL: a write to a rank that has
  // gone away (rank 0 stopped while this one was frozen) raised SIGPIPE and killed this
  // rank silently (exit 141, about one run in ten of the hung-rank test) before it could say
  // which rank stopped. Ignored, the write fails with EPIPE and the collective's error
  // names the culprit. Process-wide, for the life of a distributed run.
  std::signal(SIGPIPE, SIG_IGN);
  return std::make_unique<GlooCommunicator>(launch, options);
}

}  // namespace upkie_rl
