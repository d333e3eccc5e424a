#include "envs/controllers/forward_balance_law.hpp"

#include <algorithm>
#include <cmath>

namespace upkie_rl {

ForwardBalanceLaw::ForwardBalanceLaw(const VelocityBalancerGains& gains, double timestep,
                                     double velocity_filter_gain, double acceleration_filter_gain)
    : gains_(gains),
      timestep_(timestep),
      velocity_filter_gain_(velocity_filter_gain),
      acceleration_filter_gain_(acceleration_filter_gain) {}

void ForwardBalanceLaw::reset() {
  position_error_ = 0.0;
  reference_velocity_ = 0.0;
  reference_acceleration_ = 0.0;
  filtered_velocity_ = 0.0;
  ground_velocity_ = 0.0;
}

double ForwardBalanceLaw::ground_velocity(const ForwardBalanceInputs& inputs) {
  const double max_change = kMaxAcceleration * timestep_;
  const double change = std::clamp(inputs.command - reference_velocity_, -max_change, max_change);
  reference_velocity_ += change;
  reference_acceleration_ +=
      acceleration_filter_gain_ * (change / timestep_ - reference_acceleration_);
  filtered_velocity_ += velocity_filter_gain_ * (inputs.odometry_velocity - filtered_velocity_);
  const double velocity_error = filtered_velocity_ - reference_velocity_;
  position_error_ = std::clamp(position_error_ + velocity_error * timestep_, -kMaxPositionError,
                               kMaxPositionError);
  const double steady_pitch = gains_.pitch_offset +
                              gains_.pitch_per_velocity * reference_velocity_ +
                              gains_.pitch_per_acceleration * reference_acceleration_;
  const double steady_command = gains_.command_offset +
                                gains_.command_per_velocity * reference_velocity_ +
                                gains_.command_per_acceleration * reference_acceleration_;
  const std::array<double, 4>& k = gains_.feedback;
  ground_velocity_ = steady_command + k[0] * (inputs.pitch - steady_pitch) +
                     k[1] * inputs.pitch_rate + k[2] * velocity_error + k[3] * position_error_ +
                     excitation_;
  return ground_velocity_;
}

double filter_gain_at_rate(double gain, double designed_timestep, double timestep) {
  // At the designed rate the gain itself: 1 - (1 - gain) rounds it in its last bit, which
  // a chaotic rollout would carry into every figure's last digits.
  if (timestep == designed_timestep) return gain;
  return 1.0 - std::pow(1.0 - gain, timestep / designed_timestep);
}

}  // namespace upkie_rl
