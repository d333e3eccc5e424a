#include "envs/kinds/velocity_env.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "envs/controllers/builtin_controllers.hpp"
#include "envs/wrappers/env_wrapper.hpp"
#include "model/joint_order.hpp"
#include "sim/random_draws.hpp"

namespace upkie_rl {

namespace {

/// Stream of the command generator, derived from a reset's seed.
constexpr std::uint64_t kCommandStream = 7;

}  // namespace

/// Refuses a height range whose deepest crouch needs leg targets beyond leg_action_scale:
/// neither the baseline nor a policy could reach it.
void VelocityEnv::check_crouch_reach(const VelocityTaskConfig& task,
                                     const VelocityCommandRanges& commands) const {
  // About the crouch, an action of zero holds every commanded height.
  if (!commands.height_command || task.leg_action_about_crouch) return;
  const CrouchPose deepest = task_.legs().crouch_pose(commands.min_height);
  const double largest = std::max(std::abs(deepest.hip), std::abs(deepest.knee));
  if (largest > task.leg_action_scale) {
    throw std::invalid_argument(
        "min_height_command " + std::to_string(commands.min_height) + " m needs leg targets of " +
        std::to_string(largest) + " rad, beyond leg_action_scale " +
        std::to_string(task.leg_action_scale) + " rad: raise leg_action_scale");
  }
}

VelocityEnv::VelocityEnv(std::unique_ptr<ServosEnv> servos, const VelocityTaskConfig& task,
                         const VelocityCommandRanges& commands)
    : ServosWrapperEnv(std::move(servos), "VelocityEnv"),
      task_(servos_->model(), task, commands.height_command),
      sampler_(commands),
      limiter_(commands.max_acceleration, commands.max_yaw_acceleration,
               commands.height_command ? commands.max_height_velocity : 0.0) {
  observation_space_ = VelocityTask::make_observation_space(
      commands.height_command, task.observe_command_acceleration, task.observe_acceleration);
  check_crouch_reach(task, commands);
  action_space_ = VelocityTask::make_action_space();
  mirror_ = VelocityTask::make_mirror_symmetry(observation_space_, action_space_);
  if (!task.base_controller.empty()) {
    try {
      base_ = make_builtin_controller(task.base_controller, *this);
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument(std::string("base_controller: ") + error.what());
    }
  }
  check_residual_options(task);
  if (task.residual_filter > 0.0 || task.residual_lag_max > 0.0) {
    residual_lag_.emplace(task.residual_filter, task.residual_lag_max, servos_->timestep(),
                          action_.size());
  }
}

void VelocityEnv::check_residual_options(const VelocityTaskConfig& task) const {
  // Each shapes the agent's residual on top of the base's action: without a base there is
  // no residual, and a silently ignored option would train something else than asked.
  const std::pair<const char*, bool> shapes_the_residual[] = {
      {"residual_filter", task.residual_filter > 0.0},
      {"residual_lag_max", task.residual_lag_max > 0.0},
      {"residual_fade_end", task.residual_fade_end > 0.0},
      {"residual_leg_gain", task.residual_leg_gain != 1.0},
  };
  for (const auto& [option, is_set] : shapes_the_residual) {
    if (is_set && !base_) {
      throw std::invalid_argument(std::string(option) + " needs a base_controller");
    }
  }
  if (task.residual_fade_end > 0.0 && task.residual_fade_start >= task.residual_fade_end) {
    throw std::invalid_argument("residual_fade_start " + std::to_string(task.residual_fade_start) +
                                " rad must be below residual_fade_end " +
                                std::to_string(task.residual_fade_end) + " rad");
  }
}

void VelocityEnv::set_command_override(const std::optional<VelocityCommand>& command) {
  if (command && !(std::isfinite(command->forward_velocity) && std::isfinite(command->yaw_rate) &&
                   std::isfinite(command->height))) {
    throw std::invalid_argument(
        "velocity command: forward_velocity, yaw_rate and height must be finite");
  }
  const VelocityCommandRanges& ranges = sampler_.ranges();
  if (command && ranges.height_command &&
      (command->height < ranges.min_height || command->height > ranges.max_height)) {
    throw std::invalid_argument("velocity command: height " + std::to_string(command->height) +
                                " m is outside [min_height_command, max_height_command] = [" +
                                std::to_string(ranges.min_height) + ", " +
                                std::to_string(ranges.max_height) + "] m");
  }
  override_ = command;
}

const VelocityCommand& VelocityEnv::refresh_target() {
  target_ = override_ ? *override_ : sampler_.command();
  return target_;
}

VelocityCommand VelocityEnv::command_rate() const {
  return limiter_.rate(target_, servos_->timestep());
}

void VelocityEnv::write_observation(const Observation& full, std::span<float> observation) const {
  // The rate only when observed: the hot path of the tasks without it does not compute it.
  const VelocityCommand rate =
      task_.config().observe_command_acceleration ? command_rate() : VelocityCommand{};
  task_.write_observation(full, action_, command(), observation, rate);
}

BaseVelocity VelocityEnv::measured_velocity() const {
  return task_.measure(*servos_->full_observation());
}

void VelocityEnv::set_randomization_scale(double scale) {
  ServosWrapperEnv::set_randomization_scale(scale);
  randomization_scale_ = scale;
  sampler_.set_scale(sampler_.ranges().curriculum_scale(scale));
}

void VelocityEnv::reset(std::optional<std::uint64_t> seed, std::span<float> observation) {
  const Observation& full = servos_->reset_servos(seed);
  if (seed) {
    const std::uint64_t command_seed = derive_seed(*seed, kCommandStream);
    sampler_.reset(&command_seed);
  } else {
    sampler_.reset(nullptr);
  }
  // A reset leaves the robot standing on straight legs.
  limiter_.start(refresh_target(), task_.legs().standing_height());
  held_command_ = command();
  held_target_ = target_;
  action_.fill(0.0f);
  previous_action_.fill(0.0f);
  write_observation(full, observation);
  if (base_) {
    base_->reset();
    std::copy(observation.begin(), observation.end(), last_observation_.begin());
  }
  if (residual_lag_) residual_lag_->reset(seed, randomization_scale_);
}

StepResult VelocityEnv::step(std::span<const float> action, std::span<float> observation) {
  previous_action_ = action_;
  clamp_to_space(action_space_, action, action_);
  if (residual_lag_) residual_lag_->apply(action_);
  if (base_) {
    base_->act(std::span<const float>(last_observation_).first(task_.observation_size()),
               base_action_);
    const double wheel_weight = residual_weight(*servos_->full_observation());
    const double leg_weight = wheel_weight * task_.config().residual_leg_gain;
    for (std::size_t i = 0; i < action_.size(); ++i) {
      const double weight = is_wheel(i) ? wheel_weight : leg_weight;
      action_[i] =
          std::clamp(static_cast<float>(base_action_[i] + weight * action_[i]), -1.0f, 1.0f);
    }
  }
  task_.servo_action(action_, *servos_->full_observation(), command(), servo_action_);
  const Observation& full = servos_->step_servos(servo_action_);
  held_command_ = command();
  held_target_ = target_;
  const StepResult result = task_.evaluate(full, held_command_, action_, previous_action_);
  sampler_.advance(servos_->timestep());
  limiter_.advance(refresh_target(), servos_->timestep());
  write_observation(full, observation);
  if (base_) std::copy(observation.begin(), observation.end(), last_observation_.begin());
  return result;
}

double VelocityEnv::residual_weight(const Observation& full) const {
  const VelocityTaskConfig& config = task_.config();
  if (config.residual_fade_end <= 0.0) return config.residual_scale;
  // The constructor checked residual_fade_start < residual_fade_end.
  const double share = std::clamp((config.residual_fade_end - VelocityTask::tilt(full)) /
                                      (config.residual_fade_end - config.residual_fade_start),
                                  0.0, 1.0);
  return config.residual_scale * share;
}

VelocityEnv* find_velocity_env(Env& env) {
  Env* current = &env;
  while (current != nullptr) {
    if (auto* velocity = dynamic_cast<VelocityEnv*>(current)) return velocity;
    auto* wrapper = dynamic_cast<EnvWrapper*>(current);
    current = wrapper != nullptr ? &wrapper->inner() : nullptr;
  }
  return nullptr;
}

const VelocityEnv* find_velocity_env(const Env& env) {
  return find_velocity_env(const_cast<Env&>(env));  // NOLINT: same walk, read-only use
}

}  // namespace upkie_rl
