#pragma once
/// @file
/// VelocityEnv: drive anywhere. The velocity-tracking task of the whole robot (legs and
/// wheels) on a ServosEnv, with random commands resampled during the episode or a command
/// set from outside.

#include <array>
#include <memory>
#include <optional>

#include "envs/controllers/controller.hpp"
#include "envs/randomization/residual_lag.hpp"
#include "envs/tasks/velocity_command_limiter.hpp"
#include "envs/tasks/velocity_command_sampler.hpp"
#include "envs/tasks/velocity_task.hpp"
#include "envs/wrappers/servos_wrapper_env.hpp"

namespace upkie_rl {

/// The task (VelocityTask: actions, observation, reward terms, terminations) with the
/// command of each step. The target is the sampler's random command, or the override when
/// one is set; the command the robot follows (observation, reward, tracking) moves toward
/// it within the acceleration limits of the ranges (VelocityCommandLimiter), from 0 at
/// reset.
///
/// Residual mode (option `base_controller`, e.g. the classical baseline's "balancer:..."
/// spec): the servo action is clamp(base + residual_scale·a) with `base` the built-in
/// controller's action for the last observation and `a` the agent's, so that a policy
/// learns corrections to a controller that already balances and drives. The base sees the
/// task's observation before the wrappers' noise; its share of the command passes the
/// servos' delay and lag (ActionLag) with the policy's, as on the robot.
class VelocityEnv final : public ServosWrapperEnv {
 public:
  /// @throws std::invalid_argument on a null servos environment, bad command ranges or a
  ///         base_controller that is not a velocity controller spec.
  VelocityEnv(std::unique_ptr<ServosEnv> servos, const VelocityTaskConfig& task,
              const VelocityCommandRanges& commands);

  /// Replaces the random commands by `command` as the target from the next observation on
  /// (that of the next reset or step: the step under way is still rewarded against the
  /// command its observation showed; the followed command ramps toward it within the
  /// acceleration limits); for a script, a runner or a browser. std::nullopt goes back to
  /// the random ones.
  /// @throws std::invalid_argument on a non-finite component, or a height outside the
  ///         command ranges' [min_height_command, max_height_command] with a height command.
  void set_command_override(const std::optional<VelocityCommand>& command);
  const std::optional<VelocityCommand>& command_override() const { return override_; }

  /// The command the robot follows now (in the last observation).
  const VelocityCommand& command() const { return limiter_.command(); }
  /// The followed command's rates over the coming step toward the target
  /// (VelocityCommandLimiter::rate): observed with observe_command_acceleration.
  VelocityCommand command_rate() const;
  /// The target the followed command moves toward (random draw or override).
  const VelocityCommand& target() const { return target_; }
  /// The command the last step was rewarded against (the one before the step).
  const VelocityCommand& last_step_command() const { return held_command_; }
  /// The target while the last step was taken.
  const VelocityCommand& last_step_target() const { return held_target_; }
  /// The base velocity and height measured after the last reset or step.
  BaseVelocity measured_velocity() const;

  /// Ranges of the random commands (the limits of a browser's commands too).
  const VelocityCommandRanges& command_ranges() const { return sampler_.ranges(); }

  VelocityTermination termination_reason() const { return task_.termination_reason(); }
  const VelocityTask& task() const { return task_; }

  /// Passes `scale` to the servos' randomisation and narrows the random commands to the
  /// ranges' curriculum_scale(scale) (VelocityCommandRanges::curriculum_start).
  void set_randomization_scale(double scale) override;
  void reset(std::optional<std::uint64_t> seed, std::span<float> observation) override;
  StepResult step(std::span<const float> action, std::span<float> observation) override;
  std::span<const std::string_view> reward_term_names() const override {
    return VelocityReward::kTermNames;
  }
  std::span<const double> reward_terms() const override { return task_.reward().terms(); }
  /// VelocityTask::make_mirror_symmetry of the spaces. With a base_controller the action
  /// is a residual, whose mirror is the same map when the controller is itself symmetric
  /// (the velocity balancer is: its wheels' yaw term changes sign with the yaw rate).
  const MirrorSymmetry* mirror_symmetry() const override { return &mirror_; }

 private:
  /// The task's observation of `full` with the last action, the followed command and,
  /// when observed, its rate.
  void write_observation(const Observation& full, std::span<float> observation) const;
  void check_crouch_reach(const VelocityTaskConfig& task,
                          const VelocityCommandRanges& commands) const;
  /// Refuses an option that shapes the residual (filter, lag, fade, leg gain) without a
  /// base controller, naming it, and a fade whose start is not below its end.
  void check_residual_options(const VelocityTaskConfig& task) const;
  /// The target of the next observation: the override, or the sampler's command.
  const VelocityCommand& refresh_target();
  /// Residual mode: the weight of the agent's action at the state `full`, residual_scale
  /// faded with the base's tilt (residual_fade_start, residual_fade_end).
  double residual_weight(const Observation& full) const;

  VelocityTask task_;
  VelocityCommandSampler sampler_;
  VelocityCommandLimiter limiter_;
  std::optional<VelocityCommand> override_;
  VelocityCommand target_;
  VelocityCommand held_command_;
  VelocityCommand held_target_;
  std::array<float, VelocityTask::kActionSize> action_{};
  std::array<float, VelocityTask::kActionSize> previous_action_{};
  std::unique_ptr<Controller> base_;  ///< Residual mode's controller, or null.
  /// Residual mode: the filter on the agent's action, or none.
  std::optional<ResidualLag> residual_lag_;
  double randomization_scale_ = 1.0;
  std::array<float, VelocityTask::kMaxObservationSize> last_observation_{};
  std::array<float, VelocityTask::kActionSize> base_action_{};
  ServoAction servo_action_{};
  MirrorSymmetry mirror_;
};

/// The VelocityEnv inside `env`'s wrappers (TimeLimit, noise, lag), or nullptr.
VelocityEnv* find_velocity_env(Env& env);
const VelocityEnv* find_velocity_env(const Env& env);

}  // namespace upkie_rl
