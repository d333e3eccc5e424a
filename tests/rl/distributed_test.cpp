#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <map>
#include <thread>

#include "common/background_process.hpp"
#include "common/loopback_launch.hpp"
#include "rl/distributed/communicator.hpp"
#include "rl/distributed/distributed_launch.hpp"

namespace upkie_rl {
namespace {

using namespace std::chrono_literals;
using testing::free_port;

DistributedLaunch launch_from(const std::map<std::string, std::string>& variables) {
  return distributed_launch_from_environment(
      [&](const std::string& name) -> std::optional<std::string> {
        const auto found = variables.find(name);
        if (found == variables.end()) return std::nullopt;
        return found->second;
      });
}

std::string error_of(const std::map<std::string, std::string>& variables) {
  try {
    launch_from(variables);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "no error";
}

TEST(DistributedLaunch, WithoutALauncherTheProcessTrainsAlone) {
  const DistributedLaunch alone = launch_from({});
  EXPECT_FALSE(alone.distributed());
  EXPECT_EQ(alone.source, "alone");
  EXPECT_FALSE(launch_from({{"WORLD_SIZE", "1"}, {"RANK", "0"}}).distributed());
  EXPECT_FALSE(launch_from({{"SLURM_NTASKS", "1"}, {"SLURM_PROCID", "0"}}).distributed());
}

TEST(DistributedLaunch, ReadsTorchrunsVariables) {
  const DistributedLaunch launch = launch_from({{"WORLD_SIZE", "4"},
                                                {"RANK", "3"},
                                                {"LOCAL_RANK", "1"},
                                                {"MASTER_ADDR", "10.0.0.7"},
                                                {"MASTER_PORT", "29400"}});
  EXPECT_TRUE(launch.distributed());
  EXPECT_EQ(launch.source, "torchrun");
  EXPECT_EQ(launch.world_size, 4);
  EXPECT_EQ(launch.rank, 3);
  EXPECT_EQ(launch.local_rank, 1);
  EXPECT_EQ(launch.master_addr, "10.0.0.7");
  EXPECT_EQ(launch.master_port, 29400);
  EXPECT_FALSE(launch.launcher_store);
  EXPECT_TRUE(launch_from({{"WORLD_SIZE", "2"},
                           {"RANK", "0"},
                           {"MASTER_ADDR", "127.0.0.1"},
                           {"MASTER_PORT", "29400"},
                           {"TORCHELASTIC_USE_AGENT_STORE", "True"}})
                  .launcher_store)
      << "torchrun's agent serves the store: rank 0 connects to it";
}

TEST(DistributedLaunch, ReadsSlurmsVariables) {
  const DistributedLaunch launch = launch_from({{"SLURM_NTASKS", "8"},
                                                {"SLURM_PROCID", "5"},
                                                {"SLURM_LOCALID", "1"},
                                                {"MASTER_ADDR", "node001"},
                                                {"MASTER_PORT", "29500"}});
  EXPECT_EQ(launch.source, "slurm");
  EXPECT_EQ(launch.world_size, 8);
  EXPECT_EQ(launch.rank, 5);
  EXPECT_EQ(launch.master_addr, "node001");
}

TEST(DistributedLaunch, NamesTheVariableAtFault) {
  const std::map<std::string, std::string> good = {
      {"WORLD_SIZE", "2"}, {"RANK", "1"}, {"MASTER_ADDR", "127.0.0.1"}, {"MASTER_PORT", "29500"}};
  auto with = [&](const std::string& name, const std::string& value) {
    auto variables = good;
    variables[name] = value;
    return variables;
  };
  auto without = [&](const std::string& name) {
    auto variables = good;
    variables.erase(name);
    return variables;
  };
  EXPECT_NE(error_of(with("RANK", "2")).find("RANK=\"2\" is not an integer in [0, 1]"),
            std::string::npos);
  EXPECT_NE(error_of(with("WORLD_SIZE", "two")).find("WORLD_SIZE=\"two\""), std::string::npos);
  EXPECT_NE(error_of(with("MASTER_PORT", "70000")).find("MASTER_PORT"), std::string::npos);
  EXPECT_NE(error_of(without("MASTER_ADDR")).find("MASTER_ADDR is not set"), std::string::npos);
  EXPECT_NE(error_of(without("RANK")).find("RANK is not set"), std::string::npos);
}

using testing::loopback_launch;

/// Options of the tests: a process that runs every rank must not end when one is abandoned.
CommunicatorOptions test_options(std::chrono::milliseconds timeout,
                                 std::function<void(const std::string&)> on_abandoned = {}) {
  CommunicatorOptions options;
  options.timeout = timeout;
  options.heartbeat_period = 200ms;
  options.abort_grace = 1s;
  options.on_abandoned = on_abandoned ? std::move(on_abandoned) : [](const std::string&) {};
  return options;
}

TEST(Communicator, TwoRanksSumAndBroadcast) {
  const int port = free_port();
  std::array<torch::Tensor, 2> sums, broadcasts;
  std::array<std::string, 2> errors;
  std::vector<std::thread> ranks;
  for (int rank = 0; rank < 2; ++rank) {
    ranks.emplace_back([&, rank] {
      try {
        const auto communicator =
            connect_communicator(loopback_launch(rank, 2, port), test_options(20s));
        EXPECT_EQ(communicator->rank(), rank);
        sums[rank] = torch::tensor({1.0f + rank, 10.0f * (rank + 1)});
        communicator->sum(sums[rank]);
        broadcasts[rank] = torch::full({3}, static_cast<double>(rank), torch::kFloat64);
        communicator->broadcast(broadcasts[rank], 1);
      } catch (const std::exception& error) {
        errors[rank] = error.what();
      }
    });
  }
  for (auto& thread : ranks) thread.join();
  for (int rank = 0; rank < 2; ++rank) {
    ASSERT_EQ(errors[rank], "") << "rank " << rank;
    EXPECT_TRUE(torch::equal(sums[rank], torch::tensor({3.0f, 30.0f})));
    EXPECT_TRUE(torch::equal(broadcasts[rank], torch::full({3}, 1.0, torch::kFloat64)));
  }
}

TEST(Communicator, ARankThatNeverComesTimesTheOthersOut) {
  const auto start = std::chrono::steady_clock::now();
  try {
    connect_communicator(loopback_launch(0, 2, free_port()), test_options(2s));
    FAIL() << "rank 0 met nobody";
  } catch (const DistributedError& error) {
    EXPECT_NE(std::string(error.what()).find("rank 0 of 2"), std::string::npos) << error.what();
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, 30s);
}

TEST(Communicator, ARankThatStopsAnsweringTimesTheOthersOut) {
  const int port = free_port();
  std::string error;
  std::thread rank0([&] {
    try {
      const auto communicator = connect_communicator(loopback_launch(0, 2, port), test_options(3s));
      torch::Tensor values = torch::ones({4});
      communicator->sum(values);  // together
      communicator->sum(values);  // rank 1 is gone
    } catch (const DistributedError& caught) {
      error = caught.what();
    }
  });
  {
    const auto communicator = connect_communicator(loopback_launch(1, 2, port), test_options(3s));
    torch::Tensor values = torch::ones({4});
    communicator->sum(values);
  }  // rank 1 leaves
  rank0.join();
  EXPECT_NE(error.find("rank 0 of 2: sum failed: rank 1 stopped answering (no heartbeat for 0.5 s"),
            std::string::npos)
      << error;
}

// Rank 1 stays alive but never reaches the second sum (its main thread is stuck): rank 0
// times out and names it as alive but behind; rank 1's heartbeat thread sees the abort and
// gives its process up.
TEST(Communicator, ARankStuckOutsideTheCollectivesIsNamedAndGivesUp) {
  const int port = free_port();
  std::string error;
  std::thread rank0([&] {
    try {
      const auto communicator = connect_communicator(loopback_launch(0, 2, port), test_options(2s));
      torch::Tensor values = torch::ones({4});
      communicator->sum(values);
      communicator->sum(values);
    } catch (const DistributedError& caught) {
      error = caught.what();
    }
  });
  std::promise<std::string> abandoned;
  std::future<std::string> reason = abandoned.get_future();
  {
    const auto communicator = connect_communicator(
        loopback_launch(1, 2, port),
        test_options(2s, [&](const std::string& why) { abandoned.set_value(why); }));
    torch::Tensor values = torch::ones({4});
    communicator->sum(values);
    ASSERT_EQ(reason.wait_for(30s), std::future_status::ready) << "rank 1 was never abandoned";
  }
  rank0.join();
  EXPECT_NE(error.find("rank 0 of 2: sum failed: rank 1 is alive but did not reach this "
                       "operation (1 behind"),
            std::string::npos)
      << error;
  const std::string why = reason.get();
  EXPECT_NE(why.find("rank 1 of 2: "), std::string::npos) << why;
  EXPECT_TRUE(why.find("the run was aborted (rank 0 of 2: sum failed") != std::string::npos ||
              why.find("rank 0 stopped") != std::string::npos)
      << why;
}

TEST(Communicator, AWorldOfOneNeedsNoNetwork) {
  const auto communicator = connect_communicator(DistributedLaunch{}, test_options(1s));
  torch::Tensor values = torch::tensor({2.0f});
  communicator->sum(values);
  EXPECT_EQ(values.item<float>(), 2.0f);
  EXPECT_EQ(communicator->world_size(), 1);
}

}  // namespace
}  // namespace upkie_rl
