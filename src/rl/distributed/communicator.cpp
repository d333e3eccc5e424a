#include "rl/distributed/communicator.hpp"

#include <torch/version.h>
#include <torch/csrc/distributed/c10d/PrefixStore.hpp>
#include <torch/csrc/distributed/c10d/ProcessGroupGloo.hpp>
#include <torch/csrc/distributed/c10d/TCPStore.hpp>

#include <algorithm>
#include <csignal>
#include <optional>
#include <string>
#include <vector>

#include "rl/distributed/c10d_log_silence.hpp"
#include "rl/distributed/master_address.hpp"
#include "rl/distributed/rank_watchdog.hpp"

namespace upkie_rl {

void Communicator::average(torch::Tensor values) {
  sum(values);
  values.div_(static_cast<double>(world_size()));
}

void Communicator::average(std::span<double> values) {
  average(
      torch::from_blob(values.data(), {static_cast<std::int64_t>(values.size())}, torch::kFloat64));
}

void Communicator::gather(std::span<const double> local,
                          const std::function<void(std::span<const double>)>& visit) {
  // Each rank fills its own slot of a zeroed buffer, and a sum gives everyone every slot:
  // first the number of values per rank, then the values.
  const int world = world_size();
  torch::Tensor counts = torch::zeros({world}, torch::kFloat64);
  counts.data_ptr<double>()[rank()] = static_cast<double>(local.size());
  sum(counts);
  const auto* count_of = counts.data_ptr<double>();
  std::int64_t widest = 0;
  for (int r = 0; r < world; ++r) widest = std::max(widest, static_cast<std::int64_t>(count_of[r]));
  if (widest == 0) return;
  torch::Tensor values = torch::zeros({world, widest}, torch::kFloat64);
  std::copy(local.begin(), local.end(), values[rank()].data_ptr<double>());
  sum(values);
  for (int r = 0; r < world; ++r) {
    visit({values[r].data_ptr<double>(), static_cast<std::size_t>(count_of[r])});
  }
}

namespace {

// libtorch 2.4 made libuv the TCPStore's default backend, but Debian 13's libtorch (2.6) is
// built without it ("use_libuv was requested but PyTorch was build without libuv
// support"): the classic backend, the only one of Debian 12's libtorch 1.13, on both.
void use_classic_store_backend([[maybe_unused]] c10d::TCPStoreOptions& options) {
#if TORCH_VERSION_MAJOR > 2 || (TORCH_VERSION_MAJOR == 2 && TORCH_VERSION_MINOR >= 4)
  options.useLibUV = false;
#endif
}

class GlooCommunicator final : public Communicator {
 public:
  GlooCommunicator(const DistributedLaunch& launch, const CommunicatorOptions& options)
      : launch_(launch) {
    // Our own messages name the cause; libtorch's retries would print a line each.
    const C10dLogSilence silence;
    const std::chrono::milliseconds timeout = options.timeout;
    wait_for_master_address(launch.master_addr, timeout, who());
    c10d::TCPStoreOptions store_options;
    store_options.port = static_cast<std::uint16_t>(launch.master_port);
    store_options.isServer = launch.rank == 0 && !launch.launcher_store;
    store_options.numWorkers = launch.world_size;
    store_options.waitWorkers = true;
    store_options.timeout = timeout;
    use_classic_store_backend(store_options);
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
      use_classic_store_backend(health_options);
      watchdog_.emplace(
          launch,
          c10::make_intrusive<c10d::PrefixStore>(
              "upkie_rl/health",
              c10::make_intrusive<c10d::TCPStore>(launch.master_addr, health_options)),
          RankWatchdogOptions{options.heartbeat_period, options.abort_grace, options.on_abandoned});
    } catch (const std::exception& error) {
      // (RankWatchdog's own std::invalid_argument, a missing on_abandoned, cannot happen:
      // connect_communicator refuses options without it before any store is made.)
      throw DistributedError(who() + ": cannot write heartbeats to the store at " + where + ": " +
                             first_line(error));
    }
  }

  ~GlooCommunicator() override = default;
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
    const std::int64_t entered = watchdog_->enter_operation();
    try {
      start()->wait();
    } catch (const std::exception& error) {
      const std::string message = who() + ": " + operation +
                                  " failed: " + watchdog_->diagnose(entered) + " (" +
                                  first_line(error) + ")";
      watchdog_->announce_abort(message);
      throw DistributedError(message);
    }
  }

  DistributedLaunch launch_;
  c10::intrusive_ptr<c10d::Store> store_;
  c10::intrusive_ptr<c10d::ProcessGroupGloo> group_;
  std::optional<RankWatchdog> watchdog_;  // Last: stopped first, while the group lives.
};

}  // namespace

std::unique_ptr<Communicator> connect_communicator(const DistributedLaunch& launch,
                                                   const CommunicatorOptions& options) {
  if (!launch.distributed()) return std::make_unique<SoloCommunicator>();
  if (!options.on_abandoned) {
    throw std::invalid_argument(
        "connect_communicator: CommunicatorOptions::on_abandoned is "
        "required (the application decides what an abandoned rank does)");
  }
  // Gloo's transport writes to its sockets without MSG_NOSIGNAL: a write to a rank that has
  // gone away (rank 0 stopped while this one was frozen) raised SIGPIPE and killed this
  // rank silently (exit 141, about one run in ten of the hung-rank test) before it could say
  // which rank stopped. Ignored, the write fails with EPIPE and the collective's error
  // names the culprit. Process-wide, for the life of a distributed run.
  std::signal(SIGPIPE, SIG_IGN);
  return std::make_unique<GlooCommunicator>(launch, options);
}

}  // namespace upkie_rl
