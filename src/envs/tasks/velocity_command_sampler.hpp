#pragma once
/// @file
/// VelocityCommandSampler: the random commands of the velocity task, drawn at reset and
/// redrawn during the episode.

#include <cstdint>
#include <random>
#include <string>

#include "base/option_table.hpp"
#include "envs/tasks/velocity_command.hpp"

namespace upkie_rl {

/// Lowest base height a height command may ask for [m]: knees at -2.3 rad, 0.2 rad inside
/// their joint limit (2.51 rad), with the wheel under the hip (LegKinematics::crouch_pose).
/// Below about 0.53 m the ankles' collision boxes touch the floor (kMaxShinTilt): lower
/// heights are for a robot description without them, or with terminate_on_contact=false.
inline constexpr double kLowestHeightCommand = 0.36;

}  // namespace upkie_rl

namespace upkie_rl {

/// Ranges of the random commands (environment options of the same names).
struct VelocityCommandRanges {
  double max_forward_velocity = 1.0;      ///< Forward velocity drawn in ± it [m/s].
  double max_yaw_rate = 1.5;              ///< Yaw rate drawn in ± it [rad/s].
  double zero_command_probability = 0.2;  ///< Share of draws that command standing still.
  double resample_time_min = 2.0;         ///< A command holds U(min, max) seconds [s].
  double resample_time_max = 5.0;         ///< 0 for min and max: one command per episode.
  /// The command the robot follows moves toward each drawn (or set) command at most this
  /// fast (VelocityCommandLimiter) [m/s²]; 0: at once (a step). 1 m/s² asks for a lean of
  /// about a/g = 0.1 rad (6°) while the speed changes, a third of what the baseline's
  /// design treats as near upright, and crosses the ±1 m/s range in 2 s, inside the
  /// shortest hold.
  double max_acceleration = 1.0;
  /// The same for the yaw rate [rad/s²]; 0 (default): steps, since turning asks for no
  /// lean (a differential wheel speed) and the controllers follow its steps.
  double max_yaw_acceleration = 0.0;
  /// The command is zero for this long after each reset, then the draws start [s]: a robot
  /// run starts standing still with no command (the reality suite's worlds use 1 s). 0
  /// (default): the first command is drawn at reset.
  double start_delay = 0.0;
  /// Whether the command has a base height (drawn here, observed, rewarded and followed by
  /// the baseline's legs). false: the legs' default pose at standing height and the
  /// observation of 20 components of the policies trained before the height command (a
  /// checkpoint that does not name the option is read with false).
  bool height_command = true;
  /// Lowest base height drawn [m]. 0.53: the crouch with the wheel under the hip
  /// (LegKinematics::crouch_pose: hips 0.41 rad, knees -0.80 rad) whose shins tilt by
  /// kMaxShinTilt, the most the ankles' collision boxes allow before they touch the floor;
  /// the joint limits alone would allow 0.36 m (kLowestHeightCommand).
  double min_height = 0.53;
  /// Highest base height drawn [m]: standing with straight legs (kStandingBaseHeight).
  double max_height = kStandingBaseHeight;
  /// Share of draws at max_height (standing); the others are uniform in [min, max].
  double standing_height_probability = 0.3;
  /// The followed height moves toward each drawn (or set) one at most this fast [m/s]; 0:
  /// at once. 0.1 m/s crouches the whole default range in 1.6 s, inside the shortest hold.
  double max_height_velocity = 0.1;
  /// Command curriculum of a training run: the share of the velocity and crouch ranges drawn
  /// while the run's randomisation scale (env.curriculum_steps) is 0; they grow linearly to
  /// the full ranges as that scale reaches 1. 1 (default): the full ranges from the start.
  /// Evaluations never set a scale and always draw the full ranges.
  double curriculum_start = 1.0;

  /// The share of the ranges drawn at randomisation scale `randomization_scale` in [0, 1]:
  /// curriculum_start + (1 - curriculum_start)·randomization_scale.
  double curriculum_scale(double randomization_scale) const {
    return curriculum_start + (1.0 - curriculum_start) * randomization_scale;
  }

  /// What is wrong, naming the option at fault: a negative or non-finite value, a
  /// probability above 1, or resample_time_min above resample_time_max; "" if nothing.
  std::string problem() const;
  /// @throws std::invalid_argument with problem(), if any.
  void validate() const;

  /// The command at rest: no velocity, the base at max_height.
  VelocityCommand rest_command() const;

  /// Declares the options max_forward_velocity, max_yaw_rate, zero_command_probability,
  /// command_resample_time_min, command_resample_time_max, command_max_acceleration and
  /// command_max_yaw_acceleration, command_start_delay, height_command, min_height_command,
  /// max_height_command, standing_height_probability, command_max_height_velocity,
  /// command_curriculum_start, and problem() as their rule.
  void declare_options(OptionTable& table);
};

/// Draws a command at reset, then a new one whenever the current one has held its drawn
/// duration; with a height command, each draw also draws a height from a generator of its
/// own (seeded from the same seed), so that the velocity commands of a seed are the same
/// with and without a height command. Allocation-free; deterministic given the seed.
class VelocityCommandSampler {
 public:
  /// @throws std::invalid_argument as VelocityCommandRanges::validate.
  explicit VelocityCommandSampler(const VelocityCommandRanges& ranges);

  /// Re-seeds the generator (when `seed` is set) and draws the episode's first command,
  /// or holds a zero command for the ranges' start_delay first.
  void reset(const std::uint64_t* seed);

  /// Advances time by `dt` [s]; returns true when a new command was drawn.
  bool advance(double dt);

  /// Multiplies the ranges of the next draws by `scale` in [0, 1] (a command curriculum).
  void set_scale(double scale) { scale_ = scale; }

  const VelocityCommand& command() const { return command_; }
  const VelocityCommandRanges& ranges() const { return ranges_; }

 private:
  void draw();
  /// A height draw of the ranges (height_command only) [m].
  double draw_height();

  VelocityCommandRanges ranges_;
  std::mt19937_64 generator_{0};
  std::mt19937_64 height_generator_{0};
  VelocityCommand command_;
  double scale_ = 1.0;
  double time_left_ = 0.0;  ///< Until the next draw [s]; infinite without resampling.
};

}  // namespace upkie_rl
