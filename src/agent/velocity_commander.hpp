#pragma once
/// @file
/// VelocityCommander: the velocity task's command while the robot runner runs.

#include <memory>

#include "agent/runner_options.hpp"
#include "agent/velocity_command_input.hpp"
#include "envs/kinds/velocity_env.hpp"
#include "envs/tasks/velocity_command_sampler.hpp"

namespace upkie_rl {

/// Holds the velocity task on a command set from outside (never the training's random
/// ones): zero (stand still, standing height) until the input gives one, each clamped to
/// the ranges the policy was trained on (clamp_to_trained), each change logged.
class VelocityCommander {
 public:
  /// @param env Outlives this object. @param input May be null: zero all along.
  VelocityCommander(VelocityEnv& env, std::unique_ptr<VelocityCommandInput> input,
                    const VelocityCommandRanges& trained);

  /// The command of the first observation (call before the environment's reset).
  void start();

  /// The command of the observation of the step about to run, which ends at `time` [s since
  /// the start] (as `rollout --commands` does: the step's observation shows the next command).
  void update(double time);

 private:
  void apply(const VelocityCommand& wanted, double time);

  VelocityEnv& env_;
  std::unique_ptr<VelocityCommandInput> input_;
  VelocityCommandRanges trained_;
};

/// `wanted` clamped to the `trained` ranges: velocities to their ±bounds, the height to
/// [min_height_command, max_height_command] (a policy without a height command: its
/// standing height, whatever is asked).
VelocityCommand clamp_to_trained(const VelocityCommand& wanted,
                                 const VelocityCommandRanges& trained);

/// The input the options ask for: `--commands FILE` (a schedule), `--commands -` (lines of
/// the standard input), `--keyboard`, or null (neither).
/// @throws std::invalid_argument on a malformed file, AgentError on a terminal that cannot
///         be set up.
std::unique_ptr<VelocityCommandInput> make_command_input(const RunnerOptions& options);

}  // namespace upkie_rl
