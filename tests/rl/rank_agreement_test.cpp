// Fault injection (issue 26, item 6): ranks started with different settings stop at the
// rendezvous, every one of them, with one line naming the first differing setting.

#include "rl/distributed/rank_agreement.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <thread>

#include "common/background_process.hpp"
#include "common/loopback_launch.hpp"

namespace upkie_rl {
namespace {

using namespace std::chrono_literals;

TEST(RankAgreement, SettingsNameEveryKeyWithItsSection) {
  TrainingConfig config;
  config.env_options = {{"frequency", "200"}};
  const std::vector<std::string> settings = agreement_settings(config);
  for (const char* expected :
       {"env.num_envs: 10", "env.options.frequency: 200", "ppo.n_steps: 2048",
        "normalize.epsilon: 1e-08", "policy.actor_hidden_sizes: [64, 64]", "seed: 0",
        "checkpoint format version: 1"}) {
    EXPECT_NE(std::find(settings.begin(), settings.end(), expected), settings.end()) << expected;
  }
}

/// The errors of two ranks that check `settings[rank]`.
std::array<std::string, 2> check_two_ranks(const std::array<TrainingConfig, 2>& configs) {
  const int port = testing::free_port();
  std::array<std::string, 2> errors;
  std::vector<std::thread> ranks;
  for (int rank = 0; rank < 2; ++rank) {
    ranks.emplace_back([&, rank] {
      CommunicatorOptions options;
      options.timeout = 20s;
      options.on_abandoned = [](const std::string&) {};
      try {
        const auto communicator =
            connect_communicator(testing::loopback_launch(rank, 2, port), options);
        check_ranks_agree(agreement_settings(configs[rank]), *communicator);
      } catch (const std::exception& error) {
        errors[rank] = error.what();
      }
    });
  }
  for (std::thread& rank : ranks) rank.join();
  return errors;
}

TEST(RankAgreement, DifferentNumEnvsStopsEveryRankNamingIt) {
  std::array<TrainingConfig, 2> configs;
  configs[1].num_envs = 4;
  const std::array<std::string, 2> errors = check_two_ranks(configs);
  const std::string expected =
      "the ranks disagree: env.num_envs is 10 on rank 0 but 4 on rank 1; start every rank with "
      "the same configuration and build";
  EXPECT_EQ(errors[0], expected);
  EXPECT_EQ(errors[1], expected);
}

TEST(RankAgreement, SameSettingsPass) {
  std::array<TrainingConfig, 2> configs;
  configs[0].env_options = configs[1].env_options = {{"frequency", "200"}};
  const std::array<std::string, 2> errors = check_two_ranks(configs);
  EXPECT_EQ(errors[0], "");
  EXPECT_EQ(errors[1], "");
}

}  // namespace
}  // namespace upkie_rl
