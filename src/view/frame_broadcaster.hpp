#pragma once
/// @file
/// FrameBroadcaster: the hand-over of frames from a simulation loop to the viewer's server
/// thread. The loop never waits for a browser: it writes each frame into a ring of fixed
/// size, and a reader that falls more than a ring behind loses the oldest frames.

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <span>
#include <vector>

namespace upkie_rl {

/// A ring of the last `capacity` frames of `frame_size` doubles, numbered from 1 as they are
/// published. One thread publishes; any thread collects. publish() takes a mutex held only
/// for a copy of one frame and allocates nothing.
class FrameBroadcaster {
 public:
  /// @throws ViewError when frame_size or capacity is zero.
  FrameBroadcaster(std::size_t frame_size, std::size_t capacity = 1024);

  std::size_t frame_size() const { return frame_size_; }
  std::size_t capacity() const { return capacity_; }

  /// Stores a copy of `frame`.
  /// @throws ViewError when frame.size() != frame_size() (nothing is stored).
  void publish(std::span<const double> frame);

  /// Number of the newest frame (0 before the first).
  std::uint64_t newest() const;

  /// What collect() gives.
  struct Collected {
    std::uint64_t newest = 0;   ///< Number of the last frame appended (or `after`).
    std::uint64_t skipped = 0;  ///< Frames after `after` no longer (or not to be) sent.
  };

  /// Appends to `frames` the frames numbered after `after`, oldest first: at most
  /// `max_frames` of them, the newest ones; older ones are counted as skipped.
  Collected collect(std::uint64_t after, std::size_t max_frames, std::vector<double>& frames) const;

 private:
  std::size_t frame_size_;
  std::size_t capacity_;
  mutable std::mutex mutex_;
  std::vector<double> ring_;  ///< capacity_ frames; frame n lives at slot (n - 1) % capacity_.
  std::uint64_t newest_ = 0;
};

}  // namespace upkie_rl
