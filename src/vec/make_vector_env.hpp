#pragma once
/// @file
/// Making vector environments from a registered id.

#include <memory>
#include <string>

#include "envs/registry.hpp"
#include "vec/vector_env.hpp"

namespace upkie_rl {

/// Most environments of one vector environment (each holds a simulator of its own).
inline constexpr std::size_t kMaxVectorEnvs = 4096;
/// Most worker threads of one vector environment.
inline constexpr std::size_t kMaxEnvThreads = 256;

/// threads = 0: synchronous; otherwise a thread pool with that many workers (the caller
/// included, capped at num_envs). Options are parsed once for all environments.
/// @throws std::invalid_argument on num_envs outside [1, kMaxVectorEnvs], threads above
/// kMaxEnvThreads, or whatever make_env throws.
std::unique_ptr<VectorEnv> make_vector_env(const std::string& id, const EnvOptions& options,
                                           std::size_t num_envs, std::size_t threads,
                                           AutoresetMode autoreset_mode = AutoresetMode::kSameStep);

}  // namespace upkie_rl
