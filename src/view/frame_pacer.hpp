#pragma once
/// @file
/// FramePacer: the viewer server's clock for frames. While browsers are connected it calls
/// its tick every send period on the server's io thread; without them it stops (no timer,
/// no wake-ups) until started again.

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <functional>

namespace upkie_rl {

class FramePacer {
 public:
  /// @param tick Sends what is due; returns whether to tick again (browsers remain).
  FramePacer(boost::asio::io_context& io, std::chrono::steady_clock::duration period,
             std::function<bool()> tick);

  /// Ticks now, then every period, unless already ticking.
  void start();

 private:
  void step();

  boost::asio::steady_timer timer_;
  std::chrono::steady_clock::duration period_;
  std::function<bool()> tick_;
  bool ticking_ = false;
};

}  // namespace upkie_rl
