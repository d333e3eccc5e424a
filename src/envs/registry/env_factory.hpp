#pragma once
/// @file
/// Making environments by id (the registry of envs/registry/registry.hpp) on their physics
/// engine: Bullet, MuJoCo, the mock or the spine. Declared apart from the registry because its
/// definition, env_factory.cpp, is an engine source (UPKIE_RL_ENGINE_SOURCES): the robot
/// runner, which links only the engine-free cores, never sees a function it could not link.

#include <functional>
#include <memory>
#include <string>

#include "envs/core/env.hpp"
#include "envs/core/env_options.hpp"

namespace upkie_rl {

/// Makes one environment.
/// @throws std::invalid_argument naming an unknown id (listing the registered ones), an
///         unknown option (listing the valid ones) or a badly typed or out-of-range value.
std::unique_ptr<Env> make_env(const std::string& id, const EnvOptions& options = {});

/// Makes environments of one id; the options are checked and parsed once, here.
using EnvFactory = std::function<std::unique_ptr<Env>()>;
EnvFactory make_env_factory(const std::string& id, const EnvOptions& options = {});

}  // namespace upkie_rl
