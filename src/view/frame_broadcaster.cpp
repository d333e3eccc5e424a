#include "view/frame_broadcaster.hpp"

#include <algorithm>
#include <string>

#include "view/view_error.hpp"

namespace upkie_rl {

FrameBroadcaster::FrameBroadcaster(std::size_t frame_size, std::size_t capacity)
    : frame_size_(frame_size), capacity_(capacity) {
  if (frame_size == 0 || capacity == 0) {
    throw ViewError("a frame broadcaster needs a positive frame size and capacity");
  }
  ring_.resize(frame_size * capacity);
}

void FrameBroadcaster::publish(std::span<const double> frame) {
  if (frame.size() != frame_size_) {
    throw ViewError("a viewer frame has " + std::to_string(frame.size()) + " values, expected " +
                    std::to_string(frame_size_));
  }
  const std::lock_guard lock(mutex_);
  const std::size_t slot = static_cast<std::size_t>(newest_ % capacity_);
  std::copy(frame.begin(), frame.end(),
            ring_.begin() + static_cast<std::ptrdiff_t>(slot * frame_size_));
  ++newest_;
}

std::uint64_t FrameBroadcaster::newest() const {
  const std::lock_guard lock(mutex_);
  return newest_;
}

FrameBroadcaster::Collected FrameBroadcaster::collect(std::uint64_t after, std::size_t max_frames,
                                                      std::vector<double>& frames) const {
  const std::lock_guard lock(mutex_);
  Collected result{std::max(after, newest_), 0};
  if (after >= newest_) {
    result.newest = after;
    return result;
  }
  const std::uint64_t available = std::min<std::uint64_t>(newest_ - after, capacity_);
  const std::uint64_t count = std::min<std::uint64_t>(available, max_frames);
  result.skipped = (newest_ - after) - count;
  for (std::uint64_t number = newest_ - count + 1; number <= newest_; ++number) {
    const std::size_t slot = static_cast<std::size_t>((number - 1) % capacity_);
    const auto first = ring_.begin() + static_cast<std::ptrdiff_t>(slot * frame_size_);
    frames.insert(frames.end(), first, first + static_cast<std::ptrdiff_t>(frame_size_));
  }
  return result;
}

}  // namespace upkie_rl
