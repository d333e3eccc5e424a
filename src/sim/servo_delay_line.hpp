#pragma once
/// @file
/// ServoDelayLine: servo commands leaving a fixed number of steps after they were sent,
/// the pure delay the environments' actuation (ActionLag) and the simulation spine's
/// (ServoActionLag) share.

#include <cstddef>
#include <vector>

#include "sim/servo_command.hpp"

namespace upkie_rl {

/// A ring of the last `delay` commands sent. Nothing is allocated after construction when
/// every delay is at most the capacity given there.
class ServoDelayLine {
 public:
  /// @param capacity The largest delay reset() will be given [steps].
  explicit ServoDelayLine(std::size_t capacity = 0) { queue_.reserve(capacity); }

  /// Restarts with a delay of `delay` steps, every command in the line `initial`.
  void reset(std::size_t delay, const ServoAction& initial) {
    queue_.assign(delay, initial);
    head_ = 0;
  }

  /// The command sent `delay` calls ago (the reset's `initial` before), `sent` entering.
  /// The reference stays valid until the next call.
  const ServoAction& push(const ServoAction& sent) {
    if (queue_.empty()) {
      delayed_ = sent;
      return delayed_;
    }
    delayed_ = queue_[head_];
    queue_[head_] = sent;
    head_ = (head_ + 1) % queue_.size();
    return delayed_;
  }

 private:
  std::vector<ServoAction> queue_;  ///< Oldest at head_.
  std::size_t head_ = 0;
  ServoAction delayed_{};
};

}  // namespace upkie_rl
