#include "rl/ppo/ppo_minibatch.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace upkie_rl {
namespace {

// A minibatch of `size` samples whose every value names its sample: row i holds
// offset + i (observations and actions: two columns, offset + i and offset + i + 0.5).
PpoMinibatch numbered_rows(std::int64_t size, float offset) {
  const torch::Tensor row = torch::arange(size, torch::kFloat32) + offset;
  const torch::Tensor pair = torch::stack({row, row + 0.5f}, 1);
  return {pair, pair.clone(), row, row.clone(), row.clone(), row.clone()};
}

std::vector<float> values_of(const torch::Tensor& tensor) {
  const torch::Tensor flat = tensor.contiguous().view({-1});
  return {flat.data_ptr<float>(), flat.data_ptr<float>() + flat.numel()};
}

TEST(PpoMinibatch, SelectRowsTakesTheSameRowsOfEveryTensorInOrder) {
  const PpoMinibatch batch = numbered_rows(4, 10.0f);
  std::vector<std::int64_t> order{2, 0, 3};
  const PpoMinibatch selected =
      select_rows(batch, torch::from_blob(order.data(), {3}, torch::kInt64));
  const std::vector<float> rows{12, 10, 13};
  EXPECT_EQ(values_of(selected.observations), (std::vector<float>{12, 12.5, 10, 10.5, 13, 13.5}));
  EXPECT_EQ(values_of(selected.actions), values_of(selected.observations));
  for (const torch::Tensor* column :
       {&selected.old_log_prob, &selected.old_values, &selected.advantages, &selected.returns}) {
    EXPECT_EQ(values_of(*column), rows);
  }
}

TEST(PpoMinibatch, ConcatenateRowsPutsTheSecondSetAfterTheFirst) {
  const PpoMinibatch both = concatenate_rows(numbered_rows(2, 0.0f), numbered_rows(1, 100.0f));
  EXPECT_EQ(values_of(both.observations), (std::vector<float>{0, 0.5, 1, 1.5, 100, 100.5}));
  EXPECT_EQ(values_of(both.actions), values_of(both.observations));
  for (const torch::Tensor* column :
       {&both.old_log_prob, &both.old_values, &both.advantages, &both.returns}) {
    EXPECT_EQ(values_of(*column), (std::vector<float>{0, 1, 100}));
  }
}

}  // namespace
}  // namespace upkie_rl
