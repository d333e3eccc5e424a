#pragma once
/// @file
/// Trailing rolling mean for plots (pandas `rolling(window, min_periods=1).mean()`),
/// skipping NaN values.

#include <cmath>
#include <cstddef>
#include <vector>

namespace upkie_rl {

/// out[i] = mean of the non-NaN values among values[i − window + 1 .. i]; NaN if none.
inline std::vector<double> rolling_mean(const std::vector<double>& values, std::size_t window) {
  std::vector<double> out(values.size(), std::nan(""));
  if (window == 0) return out;
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isnan(values[i])) {
      sum += values[i];
      ++count;
    }
    if (i >= window && !std::isnan(values[i - window])) {
      sum -= values[i - window];
      --count;
    }
    if (count > 0) out[i] = sum / static_cast<double>(count);
  }
  return out;
}

}  // namespace upkie_rl
