#pragma once
/// @file
/// RewardTermStatistics: the mean of each reward term's episode sum over the last finished
/// episodes, logged beside the return (`episode/reward_<term>`).

#include <cstddef>
#include <span>
#include <vector>

namespace upkie_rl {

/// A window over the last `capacity` finished episodes of `num_terms` terms each, in
/// storage allocated once (add() allocates nothing).
class RewardTermStatistics {
 public:
  RewardTermStatistics(std::size_t num_terms, std::size_t capacity = 100);

  /// Records the term sums of a finished episode (num_terms values; others are ignored).
  void add(std::span<const double> episode_terms);

  std::size_t num_terms() const { return num_terms_; }
  /// Episodes in the window.
  std::size_t size() const { return count_; }
  /// Mean of term `term` over the window; NaN when empty.
  double mean(std::size_t term) const;

 private:
  std::size_t num_terms_;
  std::size_t capacity_;
  std::vector<double> window_;  ///< capacity x num_terms, a ring.
  std::size_t next_ = 0;
  std::size_t count_ = 0;
};

}  // namespace upkie_rl
