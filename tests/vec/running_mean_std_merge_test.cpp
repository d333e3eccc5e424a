#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "vec/running_mean_std.hpp"

namespace upkie_rl {
namespace {

std::vector<double> random_rows(std::size_t rows, std::size_t size, double offset,
                                std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(offset, 2.0);
  std::vector<double> batch(rows * size);
  for (double& value : batch) value = normal(rng);
  return batch;
}

// Two processes start from the same merged statistics, each adds its own batches, then
// they merge: both end with the statistics of one process that saw every batch.
TEST(RunningMeanStdMerge, TwoProcessesEndWithTheStatisticsOfAllTheirBatches) {
  RunningMeanStd reference(3);
  reference.update(std::span<const double>(random_rows(50, 3, 0.0, 1)));
  RunningMeanStd merged_a = reference, merged_b = reference;
  RunningMeanStd a = reference, b = reference;
  const auto batch_a1 = random_rows(40, 3, 5.0, 2), batch_a2 = random_rows(7, 3, -1.0, 3);
  const auto batch_b = random_rows(90, 3, 10.0, 4);
  a.update(std::span<const double>(batch_a1));
  a.update(std::span<const double>(batch_a2));
  b.update(std::span<const double>(batch_b));
  for (const auto* batch : {&batch_a1, &batch_a2, &batch_b}) {
    reference.update(std::span<const double>(*batch));
  }
  // The sum over processes, played out by hand: each side's contribution is captured,
  // then both get the total.
  std::vector<double> from_a, from_b;
  const auto capture = [](std::vector<double>& into) {
    return [&into](std::span<double> values) { into.assign(values.begin(), values.end()); };
  };
  RunningMeanStd a_probe = a, merged_a_probe = merged_a;
  a_probe.merge_across_processes(merged_a_probe, capture(from_a));
  RunningMeanStd b_probe = b, merged_b_probe = merged_b;
  b_probe.merge_across_processes(merged_b_probe, capture(from_b));
  const auto add_both = [&](std::span<double> values) {
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = from_a[i] + from_b[i];
  };
  a.merge_across_processes(merged_a, add_both);
  b.merge_across_processes(merged_b, add_both);
  EXPECT_DOUBLE_EQ(a.count(), reference.count());
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(a.mean()[i], b.mean()[i]);
    EXPECT_EQ(a.var()[i], b.var()[i]);
    EXPECT_NEAR(a.mean()[i], reference.mean()[i], 1e-10);
    EXPECT_NEAR(a.var()[i], reference.var()[i], 1e-9);
    EXPECT_EQ(merged_a.mean()[i], a.mean()[i]);
  }
  // Nothing new on either side: a merge changes nothing.
  const RunningMeanStd before = a;
  a.merge_across_processes(merged_a, [](std::span<double> values) {
    for (double& value : values) value *= 2.0;  // two processes that added nothing
  });
  EXPECT_EQ(a.mean(), before.mean());
  EXPECT_EQ(a.count(), before.count());
}

}  // namespace
}  // namespace upkie_rl
