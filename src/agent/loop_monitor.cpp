#include "agent/loop_monitor.hpp"

#include <algorithm>
#include <cmath>

#include "agent/agent_error.hpp"

namespace upkie_rl {
namespace {

constexpr double kBinWidth = 5e-6;       // [s]
constexpr std::size_t kNumBins = 40000;  // Up to 200 ms.
constexpr double kMissFactor = 1.5;

}  // namespace

LoopMonitor::LoopMonitor(double period, int max_consecutive_misses, double max_cycle_periods)
    : period_(period),
      max_consecutive_misses_(max_consecutive_misses),
      max_cycle_periods_(max_cycle_periods),
      histogram_(kNumBins, 0) {
  if (!(period > 0.0 && std::isfinite(period))) {
    throw AgentError("loop monitor: the period must be positive and finite");
  }
}

void LoopMonitor::on_cycle_start(Clock::time_point now) {
  if (!last_start_) {
    last_start_ = now;
    return;
  }
  const double period = std::chrono::duration<double>(now - *last_start_).count();
  last_start_ = now;
  last_period_ = period;
  ++cycles_;
  sum_ += period;
  max_ = std::max(max_, period);
  const auto bin = static_cast<std::size_t>(std::max(0.0, period) / kBinWidth);
  ++histogram_[std::min(bin, kNumBins - 1)];
  last_missed_ = period > kMissFactor * period_;
  if (!last_missed_) {
    consecutive_misses_ = 0;
    return;
  }
  ++misses_;
  ++consecutive_misses_;
  if (period > max_cycle_periods_ * period_) {
    throw SupervisorTrip("loop overrun: one cycle took " +
                         std::to_string(std::lround(period * 1e3)) + " ms, more than " +
                         std::to_string(max_cycle_periods_) + " periods of " +
                         std::to_string(period_ * 1e3) + " ms");
  }
  if (consecutive_misses_ >= max_consecutive_misses_) {
    throw SupervisorTrip("loop overrun: " + std::to_string(consecutive_misses_) +
                         " deadlines missed in a row (cycles longer than " +
                         std::to_string(kMissFactor * period_ * 1e3) + " ms)");
  }
}

LoopStatistics LoopMonitor::statistics() const {
  LoopStatistics statistics;
  statistics.cycles = cycles_;
  statistics.deadline_misses = misses_;
  statistics.max_period = max_;
  if (cycles_ == 0) return statistics;
  statistics.mean_period = sum_ / static_cast<double>(cycles_);
  const auto rank = static_cast<std::int64_t>(std::ceil(0.99 * static_cast<double>(cycles_)));
  std::int64_t seen = 0;
  for (std::size_t bin = 0; bin < kNumBins; ++bin) {
    seen += histogram_[bin];
    if (seen >= rank) {
      statistics.p99_period = std::min(max_, (static_cast<double>(bin) + 1.0) * kBinWidth);
      break;
    }
  }
  return statistics;
}

}  // namespace upkie_rl
