#pragma once
/// @file
/// A one-line training progress bar on stderr: steps, steps/s, ETA and recent mean return.

#include <cstdint>
#include <cstdio>
#include <string>

namespace upkie_rl::apps {

class ProgressBar {
 public:
  /// Redraws in place when `stream` is a terminal, within the terminal's width (read at
  /// each update, so a resized window is followed; the bar shrinks and the least useful
  /// fields go first, so the line never wraps); otherwise prints a full line every 5%.
  explicit ProgressBar(std::int64_t total, std::FILE* stream = stderr);

  /// Shows `done` of total steps at `steps_per_second`, with the mean return (NaN: none).
  void update(std::int64_t done, double steps_per_second, double mean_return);

  /// Ends the line.
  void finish();

 private:
  /// Columns of the terminal (COLUMNS, else 80, when the size is unknown).
  int terminal_columns() const;

  std::int64_t total_;
  std::FILE* stream_;
  bool interactive_;
  int last_printed_percent_ = -1;
};

/// The progress line in at most `columns` characters: the bar takes what the fields leave,
/// from 30 characters down to 10, then fields go (ETA, steps/s, return, total).
std::string progress_line(double fraction, const std::string& steps, const std::string& total,
                          const std::string& speed, const std::string& eta,
                          const std::string& returns, int columns);

/// "1,234,567".
std::string with_thousands(std::int64_t value);
/// "1:02:03" or "02:03".
std::string format_duration(double seconds);

}  // namespace upkie_rl::apps
