#pragma once
/// @file
/// fixed_text: a number with a fixed count of decimals for tables and CSV files, "-" when
/// it is not finite (an RMS without any step, a mean of no episodes).

#include <cmath>
#include <cstdio>
#include <string>

namespace upkie_rl::apps {

/// `value` with `decimals` decimals ("0.153"), or "-" when it is NaN or infinite.
inline std::string fixed_text(double value, int decimals = 1) {
  if (!std::isfinite(value)) return "-";
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  return text;
}

}  // namespace upkie_rl::apps
