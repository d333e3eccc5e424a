#include "envs/velocity_command_sampler.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "sim/random_draws.hpp"

namespace upkie_rl {

namespace {

void check_non_negative(const char* option, double value) {
  if (!std::isfinite(value) || value < 0.0) {
    throw std::invalid_argument(std::string(option) + " must be finite and non-negative, got " +
                                std::to_string(value));
  }
}

}  // namespace

void VelocityCommandRanges::validate() const {
  check_non_negative("max_forward_velocity", max_forward_velocity);
  check_non_negative("max_yaw_rate", max_yaw_rate);
  check_non_negative("zero_command_probability", zero_command_probability);
  check_non_negative("command_resample_time_min", resample_time_min);
  check_non_negative("command_resample_time_max", resample_time_max);
  if (zero_command_probability > 1.0) {
    throw std::invalid_argument("zero_command_probability must be at most 1, got " +
                                std::to_string(zero_command_probability));
  }
  if (resample_time_min > resample_time_max) {
    throw std::invalid_argument("command_resample_time_min (" + std::to_string(resample_time_min) +
                                ") exceeds command_resample_time_max (" +
                                std::to_string(resample_time_max) + ")");
  }
}

VelocityCommandSampler::VelocityCommandSampler(const VelocityCommandRanges& ranges)
    : ranges_(ranges) {
  ranges_.validate();
}

void VelocityCommandSampler::reset(const std::uint64_t* seed) {
  if (seed != nullptr) generator_.seed(*seed);
  draw();
}

bool VelocityCommandSampler::advance(double dt) {
  time_left_ -= dt;
  if (time_left_ > 0.0) return false;
  draw();
  return true;
}

void VelocityCommandSampler::draw() {
  // The same number of draws whatever the outcome, so that a seed fixes the whole sequence.
  const double zero_draw = uniform_unit(generator_);
  const double forward = uniform_symmetric(generator_, scale_ * ranges_.max_forward_velocity);
  const double yaw = uniform_symmetric(generator_, scale_ * ranges_.max_yaw_rate);
  const double hold =
      uniform_between(generator_, ranges_.resample_time_min, ranges_.resample_time_max);
  const bool zero = zero_draw < ranges_.zero_command_probability;
  command_.forward_velocity = zero ? 0.0 : forward;
  command_.yaw_rate = zero ? 0.0 : yaw;
  time_left_ = ranges_.resample_time_max > 0.0 ? hold : std::numeric_limits<double>::infinity();
}

}  // namespace upkie_rl
