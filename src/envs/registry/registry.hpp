#pragma once
/// @file
/// The registry of environment ids: `Upkie-{Bullet,MuJoCo,Mock,Spine}-{Servos,Pendulum,
/// Gyropod,ServosTask,Velocity}`, with `Upkie-PyBullet-*` accepted as an alias of `Upkie-Bullet-*`.
///
/// Kinds: Servos (ServosEnv), Pendulum (PendulumEnv + TimeLimit 300), Gyropod (GyropodEnv),
/// ServosTask (the seed's full-servos task chain: ServosTaskEnv + TimeLimit 300),
/// Velocity (VelocityEnv at 50 Hz + TimeLimit 1000, 20 s).
/// Options (key=value, see env_option_help()) are parsed into typed settings once, when the
/// environment or factory is made.
///
/// This header is the engine-free half, implemented in registry.cpp (the envs core, which the
/// robot runner links); making environments on a physics engine is declared in
/// envs/registry/env_factory.hpp, beside its engine-only definition.

#include <string>
#include <vector>

#include "base/option_table.hpp"
#include "envs/core/env.hpp"
#include "envs/core/env_options.hpp"

namespace upkie_rl {

/// The option that truncates every environment's episodes after this many agent steps (0:
/// never); named once for the registry and for the callers that lift the limit (a suite's
/// episodes in seconds, the robot's runner, the driving page).
inline constexpr const char* kMaxEpisodeStepsOption = "max_episode_steps";

/// Canonical ids that make_env (env_factory.hpp) accepts (aliases not listed).
std::vector<std::string> registered_env_ids();

/// "name: help (default value)" for each option `id` accepts.
/// @throws std::invalid_argument on an unknown id.
std::vector<std::string> env_option_help(const std::string& id);

/// The options of `options` (given to `source_id`) that define the task rather than the
/// conditions (OptionInfo::randomization) and that `target_id` accepts, in order: what a
/// policy trained on source_id needs to be rolled out on target_id.
/// @throws std::invalid_argument on an unknown id.
EnvOptions task_options(const std::string& source_id, const EnvOptions& options,
                        const std::string& target_id);

/// `recorded`, the options a configuration recorded for `id` (a checkpoint's env.options),
/// preceded by name=OptionInfo::recorded_default for each option it does not name that has
/// one: the options that rebuild the environment it was recorded with, although defaults
/// changed since (the velocity task's height command, its leg_action_scale).
/// @throws std::invalid_argument on an unknown id.
EnvOptions with_recorded_defaults(const std::string& id, const EnvOptions& recorded);

/// `options` followed by name=current default for each option of `id` with an
/// OptionInfo::recorded_default that `options` does not name: what a training records,
/// so that with_recorded_defaults reads its checkpoints back as they were made.
/// @throws std::invalid_argument on an unknown id.
EnvOptions with_pinned_defaults(const std::string& id, const EnvOptions& options);

/// The options `id` accepts, typed, with their defaults and bounds.
/// @throws std::invalid_argument on an unknown id.
std::vector<OptionInfo> env_option_info(const std::string& id);

}  // namespace upkie_rl
