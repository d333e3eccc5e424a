/// PushSchedule's directions: with push_direction any, push_sagittal_share of the pushes
/// point along the heading (forward and backward alike) and the rest anywhere.

#include "envs/randomization/push_schedule.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace upkie_rl {
namespace {

/// How the pushes of one long episode point, heading along x.
struct DirectionCounts {
  int pushes = 0;
  int forward = 0;   ///< Exactly along +x.
  int backward = 0;  ///< Exactly along -x.
  int sideways = 0;  ///< More across the heading than along it.

  /// The share of the pushes `count` is.
  double share(int count) const { return static_cast<double>(count) / pushes; }
};

DirectionCounts count_directions(double sagittal_share, std::uint64_t seed) {
  PushSettings settings;
  settings.force = 20.0;
  settings.force_min = 10.0;
  settings.duration = 0.1;
  settings.start = 0.0;
  settings.interval = 1.0;
  settings.direction = PushDirection::kAny;
  settings.sagittal_share = sagittal_share;
  PushSchedule schedule;
  schedule.reset(settings, 1.0, seed);
  DirectionCounts counts;
  bool pushing = false;
  for (int step = 0; step < 50 * 400; ++step) {  // 400 windows of 1 s at 50 Hz
    const Eigen::Vector3d force = schedule.force(0.02 * step, 0.0);
    const bool starts = !force.isZero() && !pushing;
    pushing = !force.isZero();
    if (!starts) continue;
    ++counts.pushes;
    if (force.y() == 0.0 && force.x() > 0.0) ++counts.forward;
    if (std::abs(force.y()) < 1e-12 && force.x() < 0.0) ++counts.backward;
    if (std::abs(force.y()) > std::abs(force.x())) ++counts.sideways;
  }
  return counts;
}

TEST(PushSchedule, WithoutASagittalShareAnyDirectionIsDrawn) {
  const DirectionCounts counts = count_directions(0.0, 7);
  EXPECT_GE(counts.pushes, 390);
  EXPECT_EQ(counts.forward + counts.backward, 0);
  // Half the directions are more across than along (binomial, 400 draws: 0.5 +- 0.025).
  EXPECT_NEAR(counts.share(counts.sideways), 0.5, 0.125);
}

TEST(PushSchedule, ASagittalShareOfOnePushesAlongTheHeadingOnly) {
  const DirectionCounts counts = count_directions(1.0, 7);
  EXPECT_EQ(counts.forward + counts.backward, counts.pushes);
  EXPECT_NEAR(counts.share(counts.forward), 0.5, 0.125);
}

TEST(PushSchedule, AHalfSagittalShareMixesBoth) {
  const DirectionCounts counts = count_directions(0.5, 7);
  const int along = counts.forward + counts.backward;
  EXPECT_NEAR(counts.share(along), 0.5, 0.125);
  EXPECT_NEAR(static_cast<double>(counts.forward) / along, 0.5, 0.15);
  // The other half point anywhere: about half of them sideways.
  EXPECT_NEAR(counts.share(counts.sideways), 0.25, 0.125);
}

}  // namespace
}  // namespace upkie_rl
