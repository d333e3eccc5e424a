#pragma once
/// @file
/// SB3-style linear schedule of the learning rate over training progress.

#include <algorithm>
#include <cstdint>

namespace upkie_rl {

/// A value going linearly from `initial` (progress remaining 1) to `final` (0).
struct LinearSchedule {
  double initial = 0.0;
  double final = 0.0;

  /// final + p·(initial − final), with p the progress remaining clamped to [0, 1].
  double operator()(double progress_remaining) const {
    const double p = std::clamp(progress_remaining, 0.0, 1.0);
    return final + p * (initial - final);
  }

  /// Progress remaining after `timesteps` of `total_timesteps`: 1 − timesteps/total.
  static double progress_remaining(std::int64_t timesteps, std::int64_t total_timesteps) {
    return 1.0 - static_cast<double>(timesteps) / static_cast<double>(total_timesteps);
  }
};

}  // namespace upkie_rl
