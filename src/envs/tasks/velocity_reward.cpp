#include "envs/tasks/velocity_reward.hpp"

#include <algorithm>
#include <cmath>

#include "envs/core/shared_options.hpp"

namespace upkie_rl {

namespace {

/// Squared tilt (|g_xy|²) at which the upright kernel is 1/e.
constexpr double kUprightWidth = 0.1;
/// Σ Δq² [rad²] at which the pose kernel is 1/e.
constexpr double kPoseWidth = 0.25;

double kernel(double error, double sigma) { return std::exp(-(error * error) / (sigma * sigma)); }

/// The linear penalty of the three tilt terms: -weight x how far `angle` is beyond `start`.
double excess_penalty(double weight, double angle, double start) {
  return -weight * std::max(0.0, angle - start);
}

}  // namespace

double tilt_from_gravity(const Eigen::Vector3d& gravity_in_base) {
  return std::acos(std::clamp(-gravity_in_base.z(), -1.0, 1.0));
}

double pitch_from_gravity(const Eigen::Vector3d& gravity_in_base) {
  return std::atan2(gravity_in_base.x(), -gravity_in_base.z());
}

double VelocityReward::operator()(const VelocityRewardInputs& inputs) {
  const double forward_error = inputs.command.forward_velocity - inputs.velocity.forward_velocity;
  const double yaw_error = inputs.command.yaw_rate - inputs.velocity.yaw_rate;
  const Eigen::Vector3d& g = inputs.gravity_in_base;
  double pose_error = 0.0;
  for (const double deviation : inputs.leg_deviation) pose_error += deviation * deviation;
  double action_change = 0.0;
  for (std::size_t i = 0; i < inputs.action.size() && i < inputs.previous_action.size(); ++i) {
    const double change = inputs.action[i] - inputs.previous_action[i];
    action_change += change * change;
  }
  // The reference is symmetric, so the deviations' mirror sums are the legs' own.
  const double hip_asymmetry = inputs.leg_deviation[0] + inputs.leg_deviation[2];
  const double knee_asymmetry = inputs.leg_deviation[1] + inputs.leg_deviation[3];
  terms_[kTrackForwardVelocity] =
      weights_.w_track_forward_velocity * kernel(forward_error, weights_.forward_velocity_sigma);
  terms_[kTrackYawRate] = weights_.w_track_yaw_rate * kernel(yaw_error, weights_.yaw_rate_sigma);
  terms_[kUpright] =
      weights_.w_upright * std::exp(-(g.x() * g.x() + g.y() * g.y()) / kUprightWidth);
  terms_[kPose] = weights_.w_pose * std::exp(-pose_error / kPoseWidth);
  terms_[kActionRate] = -weights_.w_action_rate * action_change;
  const double height_error =
      inputs.track_height ? inputs.command.height - inputs.velocity.height : 0.0;
  terms_[kTrackHeight] = inputs.track_height
                             ? weights_.w_track_height * kernel(height_error, weights_.height_sigma)
                             : 0.0;
  terms_[kHeightError] = -weights_.w_height_error * std::abs(height_error);
  const double capped_forward_error = std::min(std::abs(forward_error), kForwardErrorCap);
  terms_[kForwardVelocityError] =
      -weights_.w_forward_velocity_error * capped_forward_error * capped_forward_error;
  terms_[kTiltExcess] =
      excess_penalty(weights_.w_tilt_excess, tilt_from_gravity(g), weights_.tilt_excess_start);
  terms_[kShinTiltExcess] = excess_penalty(weights_.w_shin_tilt_excess, inputs.shin_tilt,
                                           weights_.shin_tilt_excess_start);
  terms_[kFloorTiltExcess] = excess_penalty(weights_.w_floor_tilt_excess, inputs.floor_tilt,
                                            weights_.floor_tilt_excess_start);
  terms_[kLegSymmetry] =
      -weights_.w_leg_symmetry * (hip_asymmetry * hip_asymmetry + knee_asymmetry * knee_asymmetry);
  double sum = 0.0;
  for (const double term : terms_) sum += term;
  return sum;
}

void VelocityRewardWeights::declare_options(OptionTable& table) {
  table.add_real("w_track_forward_velocity", &w_track_forward_velocity, 0.0, kOptionHuge,
                 "reward weight of forward velocity tracking");
  table.add_real("w_track_yaw_rate", &w_track_yaw_rate, 0.0, kOptionHuge,
                 "reward weight of yaw rate tracking");
  table.add_real("w_upright", &w_upright, 0.0, kOptionHuge, "reward weight of uprightness");
  table.add_real("w_pose", &w_pose, 0.0, kOptionHuge,
                 "reward weight of the legs' closeness to the default pose");
  table.add_real("w_action_rate", &w_action_rate, 0.0, kOptionHuge,
                 "penalty weight of the squared action change");
  table.add_real("forward_velocity_sigma", &forward_velocity_sigma, 1e-6, kOptionHuge,
                 "width of the forward velocity tracking kernel [m/s]");
  table.add_real("yaw_rate_sigma", &yaw_rate_sigma, 1e-6, kOptionHuge,
                 "width of the yaw rate tracking kernel [rad/s]");
  table.add_real("w_track_height", &w_track_height, 0.0, kOptionHuge,
                 "reward weight of base height tracking (with height_command)");
  table.add_real("height_sigma", &height_sigma, 1e-6, kOptionHuge,
                 "width of the base height tracking kernel [m]");
  table.add_real("w_leg_symmetry", &w_leg_symmetry, 0.0, kOptionHuge,
                 "penalty weight of the legs' squared difference from their mirror image");
  table.add_real("w_height_error", &w_height_error, 0.0, kOptionHuge,
                 "penalty weight of the absolute base height error [1/m] (with height_command)");
  table.add_real("w_tilt_excess", &w_tilt_excess, 0.0, kOptionHuge,
                 "penalty weight of the base's tilt beyond tilt_excess_start [1/rad]");
  table.add_real("tilt_excess_start", &tilt_excess_start, 0.0, 1.5,
                 "tilt [rad] from which w_tilt_excess's penalty grows");
  table.add_real("w_shin_tilt_excess", &w_shin_tilt_excess, 0.0, kOptionHuge,
                 "penalty weight of the larger shin tilt beyond shin_tilt_excess_start [1/rad]");
  table.add_real("shin_tilt_excess_start", &shin_tilt_excess_start, 0.0, 1.5,
                 "shin tilt [rad] from which w_shin_tilt_excess's penalty grows");
  table.add_real("w_floor_tilt_excess", &w_floor_tilt_excess, 0.0, kOptionHuge,
                 "penalty weight of the base's tilt from the floor's normal beyond "
                 "floor_tilt_excess_start [1/rad]");
  table.add_real("floor_tilt_excess_start", &floor_tilt_excess_start, 0.0, 1.5,
                 "tilt from the floor's normal [rad] from which w_floor_tilt_excess's penalty "
                 "grows");
  table.add_real("w_forward_velocity_error", &w_forward_velocity_error, 0.0, kOptionHuge,
                 "penalty weight of the squared forward velocity error [s^2/m^2], capped at 1 m/s");
}

}  // namespace upkie_rl
