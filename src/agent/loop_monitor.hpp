#pragma once
/// @file
/// LoopMonitor: the robot runner's loop timing (periods, deadline misses, overruns).

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace upkie_rl {

/// The timing of a run, for the exit summary.
struct LoopStatistics {
  std::int64_t cycles = 0;           ///< Periods measured (cycles after the first).
  double mean_period = 0.0;          ///< [s]
  double p99_period = 0.0;           ///< 99th percentile, to the histogram's 5 us bins [s].
  double max_period = 0.0;           ///< [s]
  std::int64_t deadline_misses = 0;  ///< Periods longer than 1.5 nominal periods.
};

/// Measures the period between the starts of successive cycles against the nominal one.
/// A cycle longer than 1.5 periods is a missed deadline; too many in a row, or one cycle
/// longer than `max_cycle_periods` periods, is an overrun that stops the run.
/// Allocation-free after construction (a fixed histogram gives the 99th percentile).
class LoopMonitor {
 public:
  using Clock = std::chrono::steady_clock;

  LoopMonitor(double period, int max_consecutive_misses, double max_cycle_periods);

  /// Records the start of a cycle at `now`.
  /// @throws SupervisorTrip naming the overrun when the bound is passed.
  void on_cycle_start(Clock::time_point now);

  /// The last period measured [s] (0 before the second cycle).
  double last_period() const { return last_period_; }
  bool last_missed() const { return last_missed_; }

  LoopStatistics statistics() const;

 private:
  double period_;
  int max_consecutive_misses_;
  double max_cycle_periods_;
  std::optional<Clock::time_point> last_start_;
  double last_period_ = 0.0;
  bool last_missed_ = false;
  int consecutive_misses_ = 0;
  std::int64_t cycles_ = 0;
  std::int64_t misses_ = 0;
  double sum_ = 0.0;
  double max_ = 0.0;
  std::vector<std::int64_t> histogram_;  // 5 us bins; the last one holds the longer periods.
};

}  // namespace upkie_rl
