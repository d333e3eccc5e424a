#pragma once
/// @file
/// A one-line training progress bar on stderr: steps, steps/s, ETA and recent mean return.

#include <cstdint>
#include <cstdio>
#include <string>

namespace upkie_rl::apps {

class ProgressBar {
 public:
  /// Redraws in place when stderr is a terminal; otherwise prints a line every 5%.
  explicit ProgressBar(std::int64_t total, std::FILE* stream = stderr);

  /// Shows `done` of total steps at `steps_per_second`, with the mean return (NaN: none).
  void update(std::int64_t done, double steps_per_second, double mean_return);

  /// Ends the line.
  void finish();

 private:
  std::int64_t total_;
  std::FILE* stream_;
  bool interactive_;
  int last_printed_percent_ = -1;
};

/// "1,234,567".
std::string with_thousands(std::int64_t value);
/// "1:02:03" or "02:03".
std::string format_duration(double seconds);

}  // namespace upkie_rl::apps
