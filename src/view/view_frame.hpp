#pragma once
/// @file
/// The frame the viewer draws: one step of a robot, as a flat row of doubles whose columns
/// are named once, here, and sent to the page with the session (the page looks them up by
/// name).

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "sim/observation.hpp"

namespace upkie_rl {

/// Columns of a frame before the joint angles (kServoNames) and the actions.
inline constexpr std::array<const char*, 13> kViewFrameLeadingFields = {
    "episode", "step",   "time",    "return",  "pitch",   "ground_position", "base_x",
    "base_y",  "base_z", "base_qw", "base_qx", "base_qy", "base_qz"};

/// Column indices; the six joint angles follow kViewBaseQz in kServoNames order, then the
/// actions.
enum ViewFrameField : std::size_t {
  kViewEpisode = 0,
  kViewStep,
  kViewTime,
  kViewReturn,
  kViewPitch,
  kViewGroundPosition,
  kViewBaseX,
  kViewBaseY,
  kViewBaseZ,
  kViewBaseQw,
  kViewBaseQx,
  kViewBaseQy,
  kViewBaseQz,
  kViewFirstJoint,
  kViewFirstAction = kViewFirstJoint + kNumServos,
};

/// At most this many actions are drawn (the full servos model has 6 × 3 components; the
/// viewer plots the first ones).
inline constexpr std::size_t kMaxViewActions = 8;

/// The column names of frames with these actions: kViewFrameLeadingFields, the joint names,
/// then "action.<name>" for the first kMaxViewActions action names.
std::vector<std::string> view_frame_fields(const std::vector<std::string>& action_names);

/// Number of columns of a frame with `num_actions` actions (capped at kMaxViewActions).
constexpr std::size_t view_frame_size(std::size_t num_actions) {
  return kViewFirstAction + (num_actions < kMaxViewActions ? num_actions : kMaxViewActions);
}

/// Where a frame comes from in its episode.
struct ViewFrameStep {
  int episode = 0;
  int step = 0;                 ///< Steps taken since the reset.
  double episode_return = 0.0;  ///< Sum of rewards so far.
};

/// Writes the frame of a simulated observation: time, pitch and ground position as the
/// robot measures them, the simulator's ground-truth base pose (NaN on a real robot) and
/// joint angles, then the action (its first frame.size() - kViewFirstAction components).
/// Allocates nothing.
/// @pre frame.size() == view_frame_size(n) with n <= action.size().
void write_view_frame(const Observation& observation, const ViewFrameStep& step,
                      std::span<const float> action, std::span<double> frame);

}  // namespace upkie_rl
