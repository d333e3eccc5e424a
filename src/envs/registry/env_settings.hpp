#pragma once
/// @file
/// What an environment id and its options resolve to, and the assembly of the task chain
/// on any backend. The engine-free half of the registry (envs/registry/registry.hpp): the engines
/// are chosen in env_factory.cpp, and the robot runner assembles the same task chain on its
/// own spine backend without linking a physics engine.

#include <memory>
#include <string>

#include "base/option_table.hpp"
#include "envs/core/env.hpp"
#include "envs/core/env_options.hpp"
#include "envs/kinds/gyropod_env.hpp"
#include "envs/kinds/pendulum_env.hpp"
#include "envs/kinds/servos_task_env.hpp"
#include "envs/randomization/action_lag.hpp"
#include "envs/randomization/init_randomization.hpp"
#include "envs/randomization/perturbation_settings.hpp"
#include "envs/tasks/velocity_command_sampler.hpp"
#include "envs/tasks/velocity_task.hpp"
#include "model/inertia_source.hpp"
#include "sim/floor_bumps.hpp"
#include "sim/simulation.hpp"
#include "spine/spine_backend.hpp"

namespace upkie_rl {

/// The backend named by an id (`Upkie-<Backend>-<Kind>`).
enum class EnvBackend { kBullet, kMujoco, kMock, kSpine };
/// The task named by an id.
enum class EnvKind { kServos, kPendulum, kGyropod, kServosTask, kVelocity };

/// A parsed environment id.
struct EnvId {
  EnvBackend backend;
  EnvKind kind;
};

/// Everything the options of an id set, with the defaults of each kind.
struct EnvSettings {
  double frequency = 200.0;  ///< Agent rate [Hz].
  int nb_substeps = 0;       ///< 0: round(1000 / frequency), physics at about 1 kHz.
  InertiaSource inertia_source = InertiaSource::kBulletBoxRule;
  InitRandomization init_rand;
  PerturbationSettings perturbations;  ///< Physics backends only.
  /// Physics backends only: part of the world, the same in every episode of a factory
  /// (MuJoCo's compiled model, shared by its environments, holds them).
  FloorBumps bumps;
  double observation_noise = 0.0;  ///< Half-width, in the observation's units.
  ActionLagSettings action_lag;
  /// Observations the agent sees, newest first (ObservationHistory); 1: the current one.
  int observation_history = 1;
  SpineBackendConfig spine;
  int max_episode_steps = 0;  ///< 0: no time limit.
  PendulumConfig pendulum;
  GyropodConfig gyropod;
  ServosTaskConfig task;
  VelocityTaskConfig velocity;
  VelocityCommandRanges commands;
};

/// Parses `Upkie-<Backend>-<Kind>` (`Upkie-PyBullet-*` is an alias of `Upkie-Bullet-*`).
/// @throws std::invalid_argument naming the id and listing the registered ones.
EnvId parse_env_id(const std::string& id);

/// The id of `kind` on `backend`, e.g. "Upkie-Spine-Pendulum".
std::string env_id_name(EnvBackend backend, EnvKind kind);

/// The options of `id`, bound to `settings`, whose defaults it sets first.
OptionTable env_option_table(const EnvId& id, EnvSettings& settings);

/// The settings of `options` given to `id` (`name` in errors), checked.
/// @throws std::invalid_argument on an unknown option, a bad value or inconsistent settings.
EnvSettings parse_env_settings(const EnvId& id, const std::string& name, const EnvOptions& options);

/// The spine backend's configuration of `settings`: its agent frequency, and the IMU's
/// acceleration required when the velocity task observes it.
SpineBackendConfig spine_backend_config(const EnvSettings& settings);

/// The task chain of `id` on `simulation`: ServosEnv, the kind's task, then the action lag,
/// observation noise, observation history and time limit wrappers that `settings` ask for.
std::unique_ptr<Env> assemble_env(const EnvId& id, const EnvSettings& settings,
                                  std::unique_ptr<Simulation> simulation,
                                  int physics_steps_per_step);

}  // namespace upkie_rl
