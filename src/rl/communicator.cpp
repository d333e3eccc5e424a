#include "rl/communicator.hpp"

#include <torch/csrc/distributed/c10d/PrefixStore.hpp>
#include <torch/csrc/distributed/c10d/ProcessGroupGloo.hpp>
#include <torch/csrc/distributed/c10d/TCPStore.hpp>

#include <string>
#include <vector>

namespace upkie_rl {

namespace {

class GlooCommunicator final : public Communicator {
 public:
  GlooCommunicator(const DistributedLaunch& launch, std::chrono::milliseconds timeout)
      : launch_(launch) {
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
    auto options = c10d::ProcessGroupGloo::Options::create(timeout);
    // Loopback worlds talk over 127.0.0.1; others over the interface the host name
    // resolves to (GLOO_SOCKET_IFNAME is not read here).
    const bool loopback = launch.master_addr == "127.0.0.1" || launch.master_addr == "localhost";
    options->devices.push_back(loopback
                                   ? c10d::ProcessGroupGloo::createDeviceForHostname("127.0.0.1")
                                   : c10d::ProcessGroupGloo::createDefaultDevice());
    options->threads = 1;
    try {
      // Our keys apart from the launcher's, in a store it may share.
      const auto keys = c10::make_intrusive<c10d::PrefixStore>("upkie_rl", store_);
      group_ = c10::make_intrusive<c10d::ProcessGroupGloo>(keys, launch.rank, launch.world_size,
                                                           options);
    } catch (const std::exception& error) {
      throw DistributedError(who() +
                             ": the Gloo process group failed to connect: " + first_line(error));
    }
  }

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
    try {
      start()->wait();
    } catch (const std::exception& error) {
      throw DistributedError(who() + ": " + operation +
                             " failed (another rank stopped or timed out): " + first_line(error));
    }
  }

  DistributedLaunch launch_;
  c10::intrusive_ptr<c10d::Store> store_;
  c10::intrusive_ptr<c10d::ProcessGroupGloo> group_;
};

}  // namespace

std::unique_ptr<Communicator> connect_communicator(const DistributedLaunch& launch,
                                                   std::chrono::milliseconds timeout) {
  if (!launch.distributed()) return std::make_unique<SoloCommunicator>();
  return std::make_unique<GlooCommunicator>(launch, timeout);
}

}  // namespace upkie_rl
