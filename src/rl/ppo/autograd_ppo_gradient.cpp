#include "rl/ppo/autograd_ppo_gradient.hpp"

#include <stdexcept>
#include <string>

#include "rl/ppo/ppo_loss.hpp"

namespace upkie_rl {

namespace {

/// `values` as a tensor of `rows` rows of `width` values (1-D when width is 0), without
/// copying: the tensor is only read, and only while the batch lives.
torch::Tensor rows_of(std::span<const float> values, std::int64_t rows, std::int64_t width,
                      const char* name) {
  const std::int64_t expected = rows * (width > 0 ? width : 1);
  if (static_cast<std::int64_t>(values.size()) != expected) {
    throw std::invalid_argument(std::string("autograd PPO gradient: '") + name + "' has " +
                                std::to_string(values.size()) + " values, expected " +
                                std::to_string(expected));
  }
  auto* data = const_cast<float*>(values.data());
  return width > 0 ? torch::from_blob(data, {rows, width}, torch::kFloat32)
                   : torch::from_blob(data, {rows}, torch::kFloat32);
}

}  // namespace

PpoLossStatistics autograd_ppo_gradient(const PpoMinibatchView& batch, ActorCritic& policy,
                                        const PpoConfig& config) {
  const std::int64_t n = batch.size;
  if (n < 1) throw std::invalid_argument("autograd PPO gradient: empty minibatch");
  const PpoMinibatch tensors{
      rows_of(batch.observations, n, policy.observation_size(), "observations"),
      rows_of(batch.actions, n, policy.action_size(), "actions"),
      rows_of(batch.old_log_prob, n, 0, "old_log_prob"),
      rows_of(batch.old_values, n, 0, "old_values"),
      rows_of(batch.advantages, n, 0, "advantages"),
      rows_of(batch.returns, n, 0, "returns")};
  const PpoLoss loss = compute_ppo_loss(
      policy.evaluate_actions(tensors.observations, tensors.actions), tensors, config);
  policy.zero_gradients();
  loss.total.backward();
  PpoLossStatistics statistics;
  statistics.total = loss.total.item<double>();
  statistics.policy_gradient_loss = loss.policy_gradient_loss.item<double>();
  statistics.value_loss = loss.value_loss.item<double>();
  statistics.entropy_loss = loss.entropy_loss.item<double>();
  statistics.approx_kl = loss.approx_kl.item<double>();
  statistics.clip_fraction = loss.clip_fraction.item<double>();
  return statistics;
}

}  // namespace upkie_rl
