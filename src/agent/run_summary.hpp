#pragma once
/// @file
/// RunSummary: what the robot runner reports when it exits.

#include <string>

#include "agent/loop_monitor.hpp"

namespace upkie_rl {

/// The outcome of one run of the robot runner.
struct RunSummary {
  /// Why the run stopped: "duration of 10 s reached", "interrupted (SIGINT or SIGTERM)", or
  /// the limit or error that stopped it.
  std::string stop_reason;
  /// True when the run ended as asked (duration reached, interrupted), false when a limit
  /// or an error stopped it.
  bool completed = false;
  LoopStatistics loop;
  int stop_cycles_sent = 0;  ///< Stop-command cycles the spine answered.
  /// True when an interrupt during the stop commands cut them short (then the Stop request).
  bool stop_cut_short = false;

  /// "summary: <cycles> cycles, loop period mean ... ms, p99 ... ms, max ... ms, <n> deadline
  /// misses; stopped: <reason>".
  std::string to_string() const;
};

}  // namespace upkie_rl
