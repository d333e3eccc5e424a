#pragma once
/// @file
/// RateLimiter: a token bucket, so that one page cannot flood the simulation with messages.

#include <chrono>

namespace upkie_rl {

/// Allows `rate` events per second on average and bursts of up to `burst` events.
class RateLimiter {
 public:
  using Clock = std::chrono::steady_clock;

  /// @throws ViewError unless rate > 0 and burst >= 1 (both finite).
  RateLimiter(double rate, double burst);

  /// Whether an event at `now` is allowed (it then takes a token).
  bool allow(Clock::time_point now);

 private:
  double rate_;
  double burst_;
  double tokens_;
  Clock::time_point last_{};
  bool started_ = false;
};

}  // namespace upkie_rl
