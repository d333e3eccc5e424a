#include "rl/ppo/ppo_minibatch.hpp"

namespace upkie_rl {

PpoMinibatch select_rows(const PpoMinibatch& batch, const torch::Tensor& index) {
  return {batch.observations.index_select(0, index), batch.actions.index_select(0, index),
          batch.old_log_prob.index_select(0, index), batch.old_values.index_select(0, index),
          batch.advantages.index_select(0, index),   batch.returns.index_select(0, index)};
}

PpoMinibatch concatenate_rows(const PpoMinibatch& first, const PpoMinibatch& second) {
  return {torch::cat({first.observations, second.observations}),
          torch::cat({first.actions, second.actions}),
          torch::cat({first.old_log_prob, second.old_log_prob}),
          torch::cat({first.old_values, second.old_values}),
          torch::cat({first.advantages, second.advantages}),
          torch::cat({first.returns, second.returns})};
}

}  // namespace upkie_rl
