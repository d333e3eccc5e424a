#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "rl/distributed/communicator.hpp"

namespace upkie_rl {
namespace {

// The learner calls every collective unconditionally: alone, each leaves the values as
// they are (so that a single-process run trains exactly as without ranks).
TEST(SoloCommunicator, EveryCollectiveIsTheIdentity) {
  SoloCommunicator solo;
  EXPECT_EQ(solo.rank(), 0);
  EXPECT_EQ(solo.world_size(), 1);
  const torch::Tensor values = torch::tensor({1.5f, -2.0f, 3.25f});
  const torch::Tensor before = values.clone();
  solo.sum(values);
  solo.broadcast(values, 0);
  solo.average(values);
  EXPECT_TRUE(torch::equal(values, before));
  std::array<double, 3> doubles{0.1, 0.2, 0.3};
  solo.average(std::span<double>(doubles));
  EXPECT_EQ(doubles, (std::array<double, 3>{0.1, 0.2, 0.3}));
}

TEST(SoloCommunicator, GatherVisitsTheLocalValuesWithoutACopy) {
  SoloCommunicator solo;
  const std::vector<double> local{1.0, 2.0, 3.0, 4.0};
  int visits = 0;
  solo.gather(local, [&](std::span<const double> values) {
    ++visits;
    EXPECT_EQ(values.data(), local.data());
    EXPECT_EQ(values.size(), local.size());
  });
  EXPECT_EQ(visits, 1);
}

TEST(Communicator, AWorldOfSeveralNeedsTheApplicationsDecisionOnAbandonment) {
  DistributedLaunch launch;
  launch.world_size = 2;
  launch.rank = 1;
  launch.master_addr = "127.0.0.1";
  launch.master_port = 1;
  CommunicatorOptions options;  // No on_abandoned.
  EXPECT_THROW(connect_communicator(launch, options), std::invalid_argument);
}

}  // namespace
}  // namespace upkie_rl
