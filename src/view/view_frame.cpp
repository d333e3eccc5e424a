#include "view/view_frame.hpp"

#include <algorithm>
#include <limits>

namespace upkie_rl {

std::vector<std::string> view_frame_fields(const std::vector<std::string>& action_names) {
  std::vector<std::string> fields(kViewFrameLeadingFields.begin(), kViewFrameLeadingFields.end());
  fields.insert(fields.end(), kServoNames.begin(), kServoNames.end());
  const std::size_t num_actions = std::min(action_names.size(), kMaxViewActions);
  for (std::size_t i = 0; i < num_actions; ++i) fields.push_back("action." + action_names[i]);
  return fields;
}

void write_view_frame(const Observation& observation, const ViewFrameStep& step,
                      std::span<const float> action, std::span<double> frame) {
  frame[kViewEpisode] = step.episode;
  frame[kViewStep] = step.step;
  frame[kViewTime] = observation.time;
  frame[kViewReturn] = step.episode_return;
  frame[kViewPitch] = observation.base_orientation.pitch;
  frame[kViewGroundPosition] = observation.wheel_odometry.position;
  if (observation.has_sim) {
    const SimBaseObservation& base = observation.sim_base;
    frame[kViewBaseX] = base.position.x();
    frame[kViewBaseY] = base.position.y();
    frame[kViewBaseZ] = base.position.z();
    frame[kViewBaseQw] = base.orientation.w();
    frame[kViewBaseQx] = base.orientation.x();
    frame[kViewBaseQy] = base.orientation.y();
    frame[kViewBaseQz] = base.orientation.z();
  } else {
    std::fill(frame.begin() + kViewBaseX, frame.begin() + kViewFirstJoint,
              std::numeric_limits<double>::quiet_NaN());
  }
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    frame[kViewFirstJoint + servo] = observation.servo[servo].position;
  }
  for (std::size_t i = kViewFirstAction; i < frame.size(); ++i) {
    frame[i] = action[i - kViewFirstAction];
  }
}

}  // namespace upkie_rl
