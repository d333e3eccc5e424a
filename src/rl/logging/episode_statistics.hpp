#pragma once
/// @file
/// Raw returns and lengths of the last finished episodes (SB3's ep_info_buffer).

#include <cstddef>
#include <cstdint>
#include <deque>

#include <nlohmann/json.hpp>

namespace upkie_rl {

/// A window over the last `capacity` finished episodes.
class EpisodeStatistics {
 public:
  explicit EpisodeStatistics(std::size_t capacity = 100) : capacity_(capacity) {}

  /// Records a finished episode: raw (un-normalised) return and length in steps.
  void add(double episode_return, std::int64_t length);

  std::size_t size() const { return returns_.size(); }
  /// Mean return of the window; NaN when empty.
  double mean_return() const;
  /// Mean length of the window; NaN when empty.
  double mean_length() const;
  /// Episodes finished since the start of training.
  std::int64_t total_episodes() const { return total_; }

  nlohmann::json state() const;
  /// Throws std::invalid_argument on a malformed state.
  void load_state(const nlohmann::json& state);

 private:
  std::size_t capacity_;
  std::deque<double> returns_;
  std::deque<std::int64_t> lengths_;
  std::int64_t total_ = 0;
};

}  // namespace upkie_rl
