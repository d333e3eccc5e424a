#pragma once
/// @file
/// A trained policy as a rollout controller (`upkie-rl rollout --model PATH`):
/// deterministic actions with the frozen normalisation saved in the model.

#include <filesystem>
#include <memory>

#include "envs/controller.hpp"
#include "envs/env.hpp"

namespace upkie_rl::apps {

/// Loads the model (a final model or checkpoint written by `upkie-rl train`) and checks that
/// its observation and action spaces are `env`'s. Throws CheckpointError naming the file and
/// the mismatch or damage.
std::unique_ptr<Controller> make_policy_controller(const std::filesystem::path& model,
                                                   const Env& env);

}  // namespace upkie_rl::apps
