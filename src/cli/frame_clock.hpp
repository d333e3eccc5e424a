#pragma once
/// @file
/// FrameClock: which steps of an episode become video frames, so that a video plays in
/// real time whatever the agent rate.

#include <cmath>

namespace upkie_rl::apps {

/// Frame k of an episode is its first step at or after k / fps seconds.
class FrameClock {
 public:
  explicit FrameClock(int fps) : fps_(fps) {}

  /// The next step is an episode's first (time 0).
  void start_episode() { next_frame_ = 0; }

  /// True when the step at simulated time `time` [s] is the next frame (and counts it).
  bool take(double time) {
    // Half a step of tolerance: at 200 Hz and 30 fps, frame k is the first step at or after
    // k / 30 s.
    if (time + 1e-9 < static_cast<double>(next_frame_) / fps_) return false;
    next_frame_ = static_cast<long>(std::floor(time * fps_ + 1e-9)) + 1;
    return true;
  }

 private:
  int fps_;
  long next_frame_ = 0;  ///< Index of the next frame within the episode.
};

}  // namespace upkie_rl::apps
