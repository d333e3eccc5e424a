#pragma once
/// @file
/// The controller of a run chosen on the command line: a trained model (`--model`) or a
/// built-in controller (`--controller`), as `rollout` and `drive` take them.

#include <memory>
#include <string>

#include "envs/controllers/controller.hpp"
#include "envs/core/env.hpp"
#include "envs/core/env_options.hpp"

namespace upkie_rl::apps {

/// The environment options of a run: `given`, completed with the model's own when `model`
/// is set (printed when there are any).
EnvOptions run_env_options(const std::string& env_id, const std::string& model,
                           const EnvOptions& given);

/// The policy of `model` when set, otherwise the built-in controller `controller` (`lqr`
/// designed on this environment's settings; the resolved gains are printed).
std::unique_ptr<Controller> make_run_controller(const std::string& env_id,
                                                const std::string& controller,
                                                const std::string& model,
                                                const EnvOptions& env_options, const Env& env);

}  // namespace upkie_rl::apps
