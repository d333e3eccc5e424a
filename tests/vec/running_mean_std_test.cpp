#include "vec/running_mean_std.hpp"

#include <gtest/gtest.h>

#include <array>

namespace upkie_rl {
namespace {

TEST(RunningMeanStd, StartsAtMeanZeroVarOne) {
  RunningMeanStd rms(3);
  EXPECT_EQ(rms.mean(), std::vector<double>(3, 0.0));
  EXPECT_EQ(rms.var(), std::vector<double>(3, 1.0));
  EXPECT_DOUBLE_EQ(rms.count(), 1e-4);
}

TEST(RunningMeanStd, HandComputedUpdate) {
  RunningMeanStd rms(2);
  // Rows (1, 2) and (3, 4): batch mean (2, 3), population var (1, 1), count 2, merged with
  // the prior (0, 1, 1e-4): mean = 2·2/2.0001, var = (1e-4 + 2 + 4·1e-4·2/2.0001)/2.0001.
  const std::array<float, 4> batch{1.0f, 2.0f, 3.0f, 4.0f};
  rms.update(batch);
  EXPECT_NEAR(rms.mean()[0], 1.9999000049997497, 1e-15);
  EXPECT_NEAR(rms.mean()[1], 2.999850007499625, 1e-15);
  EXPECT_NEAR(rms.var()[0], 1.0001999800015, 1e-14);
  EXPECT_NEAR(rms.var()[1], 1.0004499550033747, 1e-14);
  EXPECT_DOUBLE_EQ(rms.count(), 2.0001);
}

TEST(RunningMeanStd, MergingBatchesMatchesTheWholeData) {
  RunningMeanStd merged(1);
  const std::array<double, 3> first{1.0, 5.0, -2.0};
  const std::array<double, 2> second{7.0, 0.5};
  merged.update(first);
  merged.update(second);
  // Whole data: mean 2.3, population var 10.56; the 1e-4 prior shifts them by ~1e-4.
  EXPECT_NEAR(merged.mean()[0], 2.3, 1e-3);
  EXPECT_NEAR(merged.var()[0], 10.56, 1e-2);
  EXPECT_NEAR(merged.count(), 5.0001, 1e-12);
}

TEST(RunningMeanStd, JsonRoundTripAndErrors) {
  RunningMeanStd rms(2);
  const std::array<float, 4> batch{1.0f, 2.0f, 3.0f, 4.0f};
  rms.update(batch);
  RunningMeanStd copy(2);
  copy.from_json(rms.to_json(), "obs");
  EXPECT_EQ(copy.mean(), rms.mean());
  EXPECT_EQ(copy.var(), rms.var());
  EXPECT_EQ(copy.count(), rms.count());
  RunningMeanStd wrong(3);
  try {
    wrong.from_json(rms.to_json(), "obs");
    FAIL();
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("obs.mean"), std::string::npos) << error.what();
  }
  nlohmann::json missing = rms.to_json();
  missing.erase("count");
  EXPECT_THROW(copy.from_json(missing, "obs"), std::invalid_argument);
  const std::array<float, 3> ragged{1.0f, 2.0f, 3.0f};
  EXPECT_THROW(rms.update(ragged), std::invalid_argument);
}

}  // namespace
}  // namespace upkie_rl
