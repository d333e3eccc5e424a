#include "rl/ppo/mirrored_rollout.hpp"

#include <algorithm>
#include <span>
#include <stdexcept>
#include <string>

#include "rl/ppo/tensor_span.hpp"

namespace upkie_rl {

MirroredRollout::MirroredRollout(const MirrorSymmetry& mirror, std::int64_t size)
    : mirror_(mirror),
      observations_(torch::zeros({size, static_cast<std::int64_t>(mirror.observation.size())})),
      actions_(torch::zeros({size, static_cast<std::int64_t>(mirror.action.size())})),
      values_(torch::zeros({size})),
      paired_index_(static_cast<std::size_t>(2 * size)) {}

void MirroredRollout::fill(const RolloutBuffer& buffer, const ActorCritic& policy) {
  if (buffer.size() != observations_.size(0) ||
      buffer.flat_observations().size(1) != observations_.size(1) ||
      buffer.flat_actions().size(1) != actions_.size(1)) {
    throw std::invalid_argument("MirroredRollout: a rollout of " + std::to_string(buffer.size()) +
                                " samples does not match the mirror's sizes");
  }
  // Stage 1: the images of the observations and actions.
  mirror_.observation.apply(tensor_values(buffer.flat_observations().contiguous()),
                            tensor_values(observations_));
  mirror_.action.apply(tensor_values(buffer.flat_actions().contiguous()), tensor_values(actions_));
  // Stage 2: their V_old, under the policy that collected the rollout (their log π_old is
  // the originals': the header says why).
  torch::NoGradGuard no_grad;
  values_.copy_(policy.value(observations_));
  // Stage 3: the rollout and its images in one set of tensors, which every epoch's
  // paired_shuffle selects rows of.
  const PpoMinibatch rollout = buffer.flat();
  combined_ = concatenate_rows(rollout, {observations_, actions_, rollout.old_log_prob, values_,
                                         rollout.advantages, rollout.returns});
}

PpoMinibatch MirroredRollout::paired_shuffle(const std::vector<std::int64_t>& permutation,
                                             std::int64_t batch_size) {
  const auto size = static_cast<std::int64_t>(permutation.size());
  std::size_t row = 0;
  for (std::int64_t begin = 0; begin < size; begin += batch_size) {
    const std::int64_t end = std::min(size, begin + batch_size);
    for (std::int64_t i = begin; i < end; ++i) paired_index_[row++] = permutation[i];
    for (std::int64_t i = begin; i < end; ++i) paired_index_[row++] = size + permutation[i];
  }
  const torch::Tensor index = torch::from_blob(paired_index_.data(), {2 * size}, torch::kInt64);
  return select_rows(combined_, index);
}

}  // namespace upkie_rl
