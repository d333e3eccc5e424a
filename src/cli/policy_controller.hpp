#pragma once
/// @file
/// A trained policy as a rollout controller (`upkie-rl rollout --model PATH`):
/// deterministic actions with the frozen normalisation saved in the model.

#include <filesystem>
#include <memory>

#include "envs/controllers/builtin_controllers.hpp"
#include "envs/controllers/controller.hpp"
#include "envs/core/env.hpp"
#include "envs/core/env_options.hpp"

namespace upkie_rl::apps {

/// Loads the model (a final model or checkpoint written by `upkie-rl train`) and checks that
/// its observation and action spaces are `env`'s. Throws CheckpointError naming the file and
/// the mismatch or damage.
std::unique_ptr<Controller> make_policy_controller(const std::filesystem::path& model,
                                                   const Env& env);

/// Makes, for controller designs (LQR, the velocity balancer), the environment `env_id`
/// with the task options of `options` and none of its randomisation: the nominal robot.
DesignEnvFactory design_env_factory(const std::string& env_id, const EnvOptions& options);

/// The environment options that the model was trained with, without its randomisation
/// ones, that `env_id` accepts (envs/registry/registry.hpp task_options), followed by `extra`
/// (which override them): the environment the policy's task needs, under the caller's conditions.
EnvOptions options_for_model(const std::filesystem::path& model, const std::string& env_id,
                             const EnvOptions& extra);

}  // namespace upkie_rl::apps
