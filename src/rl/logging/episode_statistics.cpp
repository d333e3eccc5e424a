#include "rl/logging/episode_statistics.hpp"

#include <limits>
#include <numeric>
#include <stdexcept>

namespace upkie_rl {

void EpisodeStatistics::add(double episode_return, std::int64_t length) {
  returns_.push_back(episode_return);
  lengths_.push_back(length);
  if (returns_.size() > capacity_) {
    returns_.pop_front();
    lengths_.pop_front();
  }
  ++total_;
}

double EpisodeStatistics::mean_return() const {
  if (returns_.empty()) return std::numeric_limits<double>::quiet_NaN();
  return std::accumulate(returns_.begin(), returns_.end(), 0.0) /
         static_cast<double>(returns_.size());
}

double EpisodeStatistics::mean_length() const {
  if (lengths_.empty()) return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(std::accumulate(lengths_.begin(), lengths_.end(), std::int64_t{0})) /
         static_cast<double>(lengths_.size());
}

nlohmann::json EpisodeStatistics::state() const {
  return {{"returns", returns_}, {"lengths", lengths_}, {"total", total_}};
}

void EpisodeStatistics::load_state(const nlohmann::json& state) {
  try {
    auto returns = state.at("returns").get<std::deque<double>>();
    auto lengths = state.at("lengths").get<std::deque<std::int64_t>>();
    const auto total = state.at("total").get<std::int64_t>();
    if (returns.size() != lengths.size() || returns.size() > capacity_) {
      throw std::invalid_argument("inconsistent sizes");
    }
    returns_ = std::move(returns);
    lengths_ = std::move(lengths);
    total_ = total;
  } catch (const std::exception& error) {
    throw std::invalid_argument(std::string("episode statistics: ") + error.what());
  }
}

}  // namespace upkie_rl
