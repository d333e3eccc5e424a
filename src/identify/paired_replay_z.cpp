#include "identify/paired_replay_z.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace upkie_rl {

double paired_replay_z(std::span<const double> worse, std::span<const double> better,
                       std::size_t per_replay) {
  if (per_replay == 0 || worse.size() != better.size() || worse.size() % per_replay != 0 ||
      worse.size() / per_replay < 2) {
    throw std::invalid_argument("paired_replay_z: " + std::to_string(worse.size()) + " and " +
                                std::to_string(better.size()) + " errors are not two or more " +
                                "replays of " + std::to_string(per_replay));
  }
  const std::size_t replays = worse.size() / per_replay;
  std::vector<double> differences(replays, 0.0);  // each replay's, summed once
  for (std::size_t replay = 0; replay < replays; ++replay) {
    for (std::size_t k = replay * per_replay; k < (replay + 1) * per_replay; ++k)
      differences[replay] += worse[k] * worse[k] - better[k] * better[k];
  }
  // Two passes (the mean, then the spread about it): the differences are small against
  // the sums of squares, so the one-pass formula would lose them.
  double mean = 0.0;
  for (const double difference : differences) mean += difference;
  mean /= static_cast<double>(replays);
  double variance = 0.0;
  for (const double difference : differences) variance += (difference - mean) * (difference - mean);
  variance /= static_cast<double>(replays - 1);
  if (variance == 0.0) {
    if (mean == 0.0) return 0.0;
    return std::copysign(std::numeric_limits<double>::infinity(), mean);
  }
  return mean / std::sqrt(variance / static_cast<double>(replays));
}

}  // namespace upkie_rl
