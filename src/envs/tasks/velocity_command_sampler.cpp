#include "envs/tasks/velocity_command_sampler.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "envs/core/shared_options.hpp"
#include "sim/random_draws.hpp"

namespace upkie_rl {

namespace {

/// Stream of the height generator, derived from the sampler's seed.
constexpr std::uint64_t kHeightStream = 1;

std::string negative_problem(const char* option, double value) {
  if (std::isfinite(value) && value >= 0.0) return "";
  return std::string(option) + " must be finite and non-negative, got " + std::to_string(value);
}

}  // namespace

std::string VelocityCommandRanges::problem() const {
  for (const auto& [option, value] :
       {std::pair{"max_forward_velocity", max_forward_velocity},
        std::pair{"max_yaw_rate", max_yaw_rate},
        std::pair{"zero_command_probability", zero_command_probability},
        std::pair{"command_resample_time_min", resample_time_min},
        std::pair{"command_resample_time_max", resample_time_max},
        std::pair{"command_max_acceleration", max_acceleration},
        std::pair{"command_max_yaw_acceleration", max_yaw_acceleration},
        std::pair{"command_start_delay", start_delay},
        std::pair{"standing_height_probability", standing_height_probability},
        std::pair{"command_max_height_velocity", max_height_velocity}}) {
    std::string negative = negative_problem(option, value);
    if (!negative.empty()) return negative;
  }
  if (zero_command_probability > 1.0) {
    return "zero_command_probability must be at most 1, got " +
           std::to_string(zero_command_probability);
  }
  if (!(curriculum_start >= 0.0 && curriculum_start <= 1.0)) {
    return "command_curriculum_start must be in [0, 1], got " + std::to_string(curriculum_start);
  }
  if (standing_height_probability > 1.0) {
    return "standing_height_probability must be at most 1, got " +
           std::to_string(standing_height_probability);
  }
  for (const auto& [option, value] :
       {std::pair{"min_height_command", min_height}, std::pair{"max_height_command", max_height}}) {
    if (!(value >= kLowestHeightCommand && value <= kStandingBaseHeight)) {
      return std::string(option) + " must be in [" + std::to_string(kLowestHeightCommand) + ", " +
             std::to_string(kStandingBaseHeight) + "] m (a deep crouch to standing), got " +
             std::to_string(value);
    }
  }
  if (min_height > max_height) {
    return "min_height_command (" + std::to_string(min_height) + ") exceeds max_height_command (" +
           std::to_string(max_height) + ")";
  }
  if (resample_time_min > resample_time_max) {
    return "command_resample_time_min (" + std::to_string(resample_time_min) +
           ") exceeds command_resample_time_max (" + std::to_string(resample_time_max) + ")";
  }
  return "";
}

void VelocityCommandRanges::validate() const { throw_problem(problem()); }

VelocityCommand VelocityCommandRanges::rest_command() const {
  VelocityCommand rest;
  rest.height = max_height;
  return rest;
}

void VelocityCommandRanges::declare_options(OptionTable& table) {
  table.add_real("max_forward_velocity", &max_forward_velocity, 0.0, kOptionHuge,
                 "random forward velocity commands in +-it [m/s]");
  table.add_real("max_yaw_rate", &max_yaw_rate, 0.0, kOptionHuge,
                 "random yaw rate commands in +-it [rad/s]");
  table.add_real("zero_command_probability", &zero_command_probability, 0.0, 1.0,
                 "share of random commands that ask to stand still");
  table.add_real("command_resample_time_min", &resample_time_min, 0.0, kOptionHuge,
                 "a random command holds U(min, max) seconds [s]");
  table.add_real("command_resample_time_max", &resample_time_max, 0.0, kOptionHuge,
                 "longest hold of a random command [s], 0 for one command per episode");
  table.add_real("command_max_acceleration", &max_acceleration, 0.0, kOptionHuge,
                 "the followed forward velocity moves toward the drawn or set command at most "
                 "this fast [m/s^2], 0 for steps");
  table.add_real("command_max_yaw_acceleration", &max_yaw_acceleration, 0.0, kOptionHuge,
                 "the followed yaw rate moves toward the drawn or set command at most this fast "
                 "[rad/s^2], 0 for steps");
  table.add_real("command_start_delay", &start_delay, 0.0, kOptionHuge,
                 "the command is zero for this long after reset, then the random commands "
                 "start [s] (a robot run starts standing still)");
  table.add_choice("height_command", &height_command, {{"true", true}, {"false", false}},
                   "the command has a base height: drawn, observed (command.height), rewarded "
                   "(track_height) and followed by the baseline's legs; false: standing, the "
                   "20-component observation of the policies trained before it");
  table.set_recorded_default("height_command", "false");
  table.add_real("min_height_command", &min_height, kLowestHeightCommand, kStandingBaseHeight,
                 "lowest random base height command [m] (0.53: the ankles clear the floor)");
  table.add_real("max_height_command", &max_height, kLowestHeightCommand, kStandingBaseHeight,
                 "highest random base height command [m] (standing: 0.557)");
  table.add_real("standing_height_probability", &standing_height_probability, 0.0, 1.0,
                 "share of random height commands at max_height_command (standing)");
  table.add_real("command_max_height_velocity", &max_height_velocity, 0.0, kOptionHuge,
                 "the followed base height moves toward the drawn or set command at most this "
                 "fast [m/s], 0 for steps");
  table.add_real("command_curriculum_start", &curriculum_start, 0.0, 1.0,
                 "share of the command ranges drawn at the start of a training run's "
                 "curriculum (env.curriculum_steps), growing to 1 with it; 1 for none");
  table.add_rule([this] { return problem(); });
}

VelocityCommandSampler::VelocityCommandSampler(const VelocityCommandRanges& ranges)
    : ranges_(ranges) {
  ranges_.validate();
}

void VelocityCommandSampler::reset(const std::uint64_t* seed) {
  if (seed != nullptr) {
    generator_.seed(*seed);
    height_generator_.seed(derive_seed(*seed, kHeightStream));
  }
  if (ranges_.start_delay > 0.0) {
    command_ = ranges_.rest_command();
    time_left_ = ranges_.start_delay;  // advance() draws the first command after it
    return;
  }
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
  command_.height = ranges_.height_command ? draw_height() : kStandingBaseHeight;
}

double VelocityCommandSampler::draw_height() {
  // Two draws whatever the outcome, as above. The curriculum's scale narrows the range
  // toward standing.
  const double standing_draw = uniform_unit(height_generator_);
  const double depth =
      uniform_between(height_generator_, 0.0, ranges_.max_height - ranges_.min_height);
  if (standing_draw < ranges_.standing_height_probability) return ranges_.max_height;
  return ranges_.max_height - scale_ * depth;
}

}  // namespace upkie_rl
