#pragma once
/// @file
/// One minibatch of a PPO rollout as six tensors, and the two row operations the update
/// builds its minibatches with: selecting rows (a shuffle) and stacking two sets of rows (a
/// rollout and its mirror images).

#include <torch/torch.h>

namespace upkie_rl {

/// One minibatch of the rollout, as stored when it was collected.
struct PpoMinibatch {
  torch::Tensor observations;  ///< batch x observation_size (normalised).
  torch::Tensor actions;       ///< batch x action_size (unclipped samples).
  torch::Tensor old_log_prob;  ///< batch.
  torch::Tensor old_values;    ///< batch: V at collection time.
  torch::Tensor advantages;    ///< batch: GAE advantages (not normalised).
  torch::Tensor returns;       ///< batch: value targets A + V.
};

/// The rows `index` (a 1-D int64 tensor) of every tensor of `batch`, in that order: copies.
PpoMinibatch select_rows(const PpoMinibatch& batch, const torch::Tensor& index);

/// The rows of `first` followed by those of `second`, tensor by tensor: copies.
PpoMinibatch concatenate_rows(const PpoMinibatch& first, const PpoMinibatch& second);

}  // namespace upkie_rl
