// The cost of publishing one viewer frame (rollout --view's per-step work) with 0, 1 and
// 10 browsers connected: the simulation thread's share should not grow with the browsers,
// whose frames the server thread sends.
#include <benchmark/benchmark.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <thread>
#include <vector>

#include "common/frame_client.hpp"
#include "view/frame_broadcaster.hpp"
#include "view/view_frame.hpp"
#include "view/view_server.hpp"

namespace {

/// A browser stand-in that reads every message on a thread of its own until destroyed.
class ReadingClient {
 public:
  explicit ReadingClient(int port) : client_(port) {
    thread_ = std::thread([this] {
      while (!stop_.load()) client_.read(std::chrono::milliseconds(100));
    });
  }
  ~ReadingClient() {
    stop_.store(true);
    thread_.join();
  }

 private:
  upkie_rl::testing::FrameClient client_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

void BM_PublishViewerFrame(benchmark::State& state) {
  const auto num_clients = static_cast<std::size_t>(state.range(0));
  auto frames = std::make_shared<upkie_rl::FrameBroadcaster>(upkie_rl::view_frame_size(1));
  upkie_rl::ViewServerConfig config;
  config.port = 0;
  upkie_rl::ViewServer server(config, "{}", frames);
  std::vector<std::unique_ptr<ReadingClient>> clients;
  for (std::size_t i = 0; i < num_clients; ++i) {
    clients.push_back(std::make_unique<ReadingClient>(server.port()));
  }
  server.wait_for_clients(num_clients, std::chrono::seconds(10));
  upkie_rl::Observation observation;
  observation.has_sim = true;
  std::vector<double> frame(upkie_rl::view_frame_size(1));
  const std::vector<float> action = {0.5f};
  for (auto _ : state) {
    observation.time += 0.005;
    upkie_rl::write_view_frame(observation, {0, 1, 2.0}, action, frame);
    frames->publish(frame);
  }
  const upkie_rl::ViewServerStatistics statistics = server.statistics();
  state.counters["frames_sent"] = static_cast<double>(statistics.frames_sent);
  state.counters["frames_skipped"] = static_cast<double>(statistics.frames_skipped);
  clients.clear();
}
BENCHMARK(BM_PublishViewerFrame)->Arg(0)->Arg(1)->Arg(10)->UseRealTime();

}  // namespace
