#include "view/frame_pacer.hpp"

#include <boost/system/error_code.hpp>

namespace upkie_rl {

FramePacer::FramePacer(boost::asio::io_context& io, std::chrono::steady_clock::duration period,
                       std::function<bool()> tick)
    : timer_(io), period_(period), tick_(std::move(tick)) {}

void FramePacer::start() {
  if (ticking_) return;
  ticking_ = true;
  step();
}

void FramePacer::step() {
  if (!tick_()) {
    ticking_ = false;
    return;
  }
  timer_.expires_after(period_);
  timer_.async_wait([this](boost::system::error_code error) {
    if (!error) step();
  });
}

}  // namespace upkie_rl
