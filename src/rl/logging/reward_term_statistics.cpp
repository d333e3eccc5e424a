#include "rl/logging/reward_term_statistics.hpp"

#include <algorithm>
#include <cmath>

namespace upkie_rl {

RewardTermStatistics::RewardTermStatistics(std::size_t num_terms, std::size_t capacity)
    : num_terms_(num_terms), capacity_(std::max<std::size_t>(capacity, 1)) {
  window_.assign(capacity_ * num_terms_, 0.0);
}

void RewardTermStatistics::add(std::span<const double> episode_terms) {
  if (num_terms_ == 0 || episode_terms.size() < num_terms_) return;
  std::copy_n(episode_terms.begin(), num_terms_, window_.begin() + next_ * num_terms_);
  next_ = (next_ + 1) % capacity_;
  count_ = std::min(count_ + 1, capacity_);
}

double RewardTermStatistics::mean(std::size_t term) const {
  if (count_ == 0 || term >= num_terms_) return std::nan("");
  double sum = 0.0;
  for (std::size_t e = 0; e < count_; ++e) sum += window_[e * num_terms_ + term];
  return sum / static_cast<double>(count_);
}

}  // namespace upkie_rl
