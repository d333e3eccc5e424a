// The cost of one gradient all-reduce of DD-PPO (Communicator::sum) over Gloo on 127.0.0.1,
// for 2 and 4 ranks run as threads of this process: a 1-float sum (the latency), the flat
// gradient of the pendulum policy (9,091 floats, 36 kB) and a larger one (100,000 floats).
// Rank 0 is timed; the other ranks follow it in lockstep.
#include <benchmark/benchmark.h>

#include <chrono>
#include <memory>
#include <thread>
#include <vector>

#include "common/background_process.hpp"
#include "common/loopback_launch.hpp"
#include "rl/distributed/communicator.hpp"

namespace {

using upkie_rl::testing::loopback_launch;

upkie_rl::CommunicatorOptions bench_options() {
  upkie_rl::CommunicatorOptions options;
  options.timeout = std::chrono::seconds(60);
  options.on_abandoned = [](const std::string&) {};
  return options;
}

void BM_GradientAllReduce(benchmark::State& state) {
  const int world_size = static_cast<int>(state.range(0));
  const std::int64_t size = state.range(1);
  const int port = upkie_rl::testing::free_port();
  // The last value says whether to go on: rank 0 writes 0 to continue, -1 to stop.
  std::vector<std::thread> followers;
  for (int rank = 1; rank < world_size; ++rank) {
    followers.emplace_back([=] {
      const auto communicator =
          upkie_rl::connect_communicator(loopback_launch(rank, world_size, port), bench_options());
      torch::Tensor values = torch::zeros({size + 1});
      while (true) {
        values[size] = 0.0f;
        communicator->sum(values);
        if (values[size].item<float>() < 0.0f) break;
      }
    });
  }
  const auto communicator =
      upkie_rl::connect_communicator(loopback_launch(0, world_size, port), bench_options());
  torch::Tensor values = torch::ones({size + 1});
  for (auto _ : state) {
    values[size] = 0.0f;
    communicator->sum(values);
  }
  values[size] = -1.0f;
  communicator->sum(values);
  for (auto& thread : followers) thread.join();
  state.SetBytesProcessed(state.iterations() * size * static_cast<std::int64_t>(sizeof(float)));
}
BENCHMARK(BM_GradientAllReduce)
    ->ArgNames({"ranks", "floats"})
    ->ArgsProduct({{2, 4}, {1, 9091, 100000}})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();

}  // namespace
