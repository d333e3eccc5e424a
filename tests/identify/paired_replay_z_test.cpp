// paired_replay_z: the paired z of two sets of replay errors, replay by replay.

#include "identify/paired_replay_z.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace upkie_rl {
namespace {

TEST(PairedReplayZ, MeanOverStandardErrorOfTheReplaysDifferences) {
  // Three replays of one error each; the differences of squares are 1, 2 and 3: mean 2,
  // standard deviation 1, standard error 1/sqrt(3).
  const std::vector<double> better = {0.0, 0.0, 0.0};
  const std::vector<double> worse = {1.0, std::sqrt(2.0), std::sqrt(3.0)};
  EXPECT_NEAR(paired_replay_z(worse, better, 1), 2.0 * std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(paired_replay_z(better, worse, 1), -2.0 * std::sqrt(3.0), 1e-12);
}

TEST(PairedReplayZ, SumsTheErrorsOfEachReplayFirst) {
  // Three replays of two errors each, whose differences of squares sum to 1, 2 and 3.
  const std::vector<double> better(6, 0.0);
  const std::vector<double> worse = {1.0, 0.0, 1.0, 1.0, 1.0, std::sqrt(2.0)};
  EXPECT_NEAR(paired_replay_z(worse, better, 2), 2.0 * std::sqrt(3.0), 1e-12);
  // Within a replay, errors that trade places do not count.
  EXPECT_EQ(paired_replay_z(std::vector<double>{0.0, 1.0, 0.0, 1.0},
                            std::vector<double>{1.0, 0.0, 1.0, 0.0}, 2),
            0.0);
}

TEST(PairedReplayZ, ADifferenceThatChangesSignIsNotSignificant) {
  const std::vector<double> better = {1.0, 2.0, 1.0, 2.0};
  const std::vector<double> worse = {2.0, 1.0, 2.0, 1.0};
  EXPECT_EQ(paired_replay_z(worse, better, 1), 0.0);
}

TEST(PairedReplayZ, TheSameDifferenceInEveryReplayIsCertain) {
  const std::vector<double> better = {1.0, 1.0, 1.0};
  const std::vector<double> worse = {2.0, 2.0, 2.0};
  EXPECT_EQ(paired_replay_z(worse, better, 1), std::numeric_limits<double>::infinity());
  EXPECT_EQ(paired_replay_z(better, worse, 1), -std::numeric_limits<double>::infinity());
}

TEST(PairedReplayZ, SizesThatAreNotTheSameReplaysAreRefused) {
  const std::vector<double> three = {1.0, 2.0, 3.0};
  const std::vector<double> four = {1.0, 2.0, 3.0, 4.0};
  EXPECT_THROW(paired_replay_z(three, four, 1), std::invalid_argument);
  EXPECT_THROW(paired_replay_z(four, four, 3), std::invalid_argument);  // not whole replays
  EXPECT_THROW(paired_replay_z(four, four, 4), std::invalid_argument);  // one replay
  EXPECT_THROW(paired_replay_z(four, four, 0), std::invalid_argument);
  try {
    paired_replay_z(three, four, 1);
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("3 and 4 errors"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace upkie_rl
