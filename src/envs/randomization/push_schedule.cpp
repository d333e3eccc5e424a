#include "envs/randomization/push_schedule.hpp"

#include <cmath>
#include <numbers>

#include "sim/random_draws.hpp"

namespace upkie_rl {

void PushSchedule::reset(const PushSettings& settings, double scale, std::uint64_t seed) {
  settings_ = settings;
  scale_ = scale;
  generator_.seed(seed);
  window_ = -1;
  started_ = false;
  force_.setZero();
  if (settings_.enabled()) draw_push(0);
}

void PushSchedule::draw_push(int window) {
  constexpr double kPi = std::numbers::pi;
  window_ = window;
  started_ = false;
  const double window_start = settings_.start + window * settings_.interval;
  push_start_ = window_start + (settings_.interval - settings_.duration) * uniform_unit(generator_);
  magnitude_ = scale_ * uniform_between(generator_, settings_.force_min, settings_.force);
  const double u = uniform_unit(generator_);
  const bool first_half = u < 0.5;
  switch (settings_.direction) {
    case PushDirection::kSagittal:
      angle_ = first_half ? 0.0 : kPi;
      break;
    case PushDirection::kForward:
      angle_ = 0.0;
      break;
    case PushDirection::kBackward:
      angle_ = kPi;
      break;
    case PushDirection::kLateral:
      angle_ = first_half ? kPi / 2.0 : -kPi / 2.0;
      break;
    case PushDirection::kAny: {
      // One draw decides both: u below the share is a push along the heading (each half of
      // the share one way), above it any direction; a share of 0 keeps the draws of before.
      const double share = settings_.sagittal_share;
      if (u < share) {
        angle_ = u < 0.5 * share ? 0.0 : kPi;
      } else {
        angle_ = 2.0 * kPi * (u - share) / (1.0 - share);
      }
      break;
    }
  }
}

Eigen::Vector3d PushSchedule::force(double time, double yaw) {
  if (!settings_.enabled()) return Eigen::Vector3d::Zero();
  // Small tolerance: times are sums of agent timesteps.
  constexpr double kEpsilon = 1e-9;
  if (started_ && time + kEpsilon >= push_start_ + settings_.duration) {
    draw_push(window_ + 1);  // the push is over; the next window's is drawn
    force_.setZero();
  }
  if (!started_ && time + kEpsilon >= push_start_) {
    started_ = true;
    const double direction = yaw + angle_;
    force_ = magnitude_ * Eigen::Vector3d(std::cos(direction), std::sin(direction), 0.0);
  }
  return started_ ? force_ : Eigen::Vector3d::Zero();
}

}  // namespace upkie_rl
