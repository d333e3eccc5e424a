#include "view/rate_limiter.hpp"

#include <algorithm>
#include <cmath>

#include "view/view_error.hpp"

namespace upkie_rl {

RateLimiter::RateLimiter(double rate, double burst) : rate_(rate), burst_(burst), tokens_(burst) {
  if (!(std::isfinite(rate) && rate > 0.0) || !(std::isfinite(burst) && burst >= 1.0)) {
    throw ViewError("rate limiter: the rate must be > 0 and the burst >= 1");
  }
}

bool RateLimiter::allow(Clock::time_point now) {
  if (started_ && now > last_) {
    const double elapsed = std::chrono::duration<double>(now - last_).count();
    tokens_ = std::min(burst_, tokens_ + elapsed * rate_);
  }
  if (!started_ || now > last_) last_ = now;
  started_ = true;
  if (tokens_ < 1.0) return false;
  tokens_ -= 1.0;
  return true;
}

}  // namespace upkie_rl
