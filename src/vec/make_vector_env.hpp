#pragma once
/// @file
/// Making vector environments from a registered id.

#include <memory>
#include <string>

#include "envs/registry/env_factory.hpp"
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

/// Two ids of one task side by side (one per engine, say Upkie-MuJoCo-Velocity and
/// Upkie-Bullet-Velocity): `mix_envs` of the `num_envs` environments, spread evenly over the
/// indices so that every worker thread gets its share, are `mix_id`'s, the others `id`'s.
/// Why: a policy trained on one engine's contacts alone meets the other's as a new floor.
/// @throws std::invalid_argument as make_vector_env, on mix_envs >= num_envs, or when the two
/// ids' observation or action spaces differ (naming both ids).
std::unique_ptr<VectorEnv> make_mixed_vector_env(
    const std::string& id, const std::string& mix_id, std::size_t mix_envs,
    const EnvOptions& options, std::size_t num_envs, std::size_t threads,
    AutoresetMode autoreset_mode = AutoresetMode::kSameStep);

/// Whether environment `index` of `num_envs` is one of the `mix_envs` spread evenly.
bool is_mixed_env(std::size_t index, std::size_t mix_envs, std::size_t num_envs);

}  // namespace upkie_rl
