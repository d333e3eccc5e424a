#include "vec/make_vector_env.hpp"

#include <algorithm>
#include <stdexcept>

#include "base/setting_bounds.hpp"
#include "envs/registry/env_factory.hpp"
#include "vec/sync_vector_env.hpp"
#include "vec/thread_pool_vector_env.hpp"

namespace upkie_rl {

namespace {

bool same_space(const BoxSpace& a, const BoxSpace& b) {
  return a.names == b.names && a.low == b.low && a.high == b.high;
}

void check_same_spaces(Env& env, Env& mix, const std::string& id, const std::string& mix_id) {
  if (!same_space(env.observation_space(), mix.observation_space()) ||
      !same_space(env.action_space(), mix.action_space())) {
    throw std::invalid_argument("environments " + id + " and " + mix_id +
                                " cannot be mixed: their observation or action spaces differ");
  }
}

}  // namespace

bool is_mixed_env(std::size_t index, std::size_t mix_envs, std::size_t num_envs) {
  return (index + 1) * mix_envs / num_envs > index * mix_envs / num_envs;
}

std::unique_ptr<VectorEnv> make_vector_env(const std::string& id, const EnvOptions& options,
                                           std::size_t num_envs, std::size_t threads,
                                           AutoresetMode autoreset_mode) {
  return make_mixed_vector_env(id, "", 0, options, num_envs, threads, autoreset_mode);
}

std::unique_ptr<VectorEnv> make_mixed_vector_env(const std::string& id, const std::string& mix_id,
                                                 std::size_t mix_envs, const EnvOptions& options,
                                                 std::size_t num_envs, std::size_t threads,
                                                 AutoresetMode autoreset_mode) {
  // Python passes these unchecked; the configuration checked them already under its keys.
  check_setting("num_envs", static_cast<std::int64_t>(num_envs), 1,
                static_cast<std::int64_t>(kMaxVectorEnvs));
  check_setting("num_threads", static_cast<std::int64_t>(threads), 0,
                static_cast<std::int64_t>(kMaxEnvThreads));
  if (mix_envs >= num_envs) {  // num_envs >= 1: a mix that leaves id no environment
    throw std::invalid_argument("mixed environments: " + std::to_string(mix_envs) + " of " +
                                std::to_string(num_envs) + " leaves none of " + id);
  }
  const EnvFactory factory = make_env_factory(id, options);
  const EnvFactory mix_factory = mix_envs > 0 ? make_env_factory(mix_id, options) : EnvFactory();
  std::vector<std::unique_ptr<Env>> envs;
  envs.reserve(num_envs);
  for (std::size_t i = 0; i < num_envs; ++i) {
    const bool mixed = is_mixed_env(i, mix_envs, num_envs);
    envs.push_back(mixed ? mix_factory() : factory());
    // Environment 0 is always id's (mix_envs < num_envs); one factory makes equal spaces.
    if (mixed) check_same_spaces(*envs.front(), *envs.back(), id, mix_id);
  }
  if (threads == 0) return std::make_unique<SyncVectorEnv>(std::move(envs), autoreset_mode);
  return std::make_unique<ThreadPoolVectorEnv>(std::move(envs), std::min(threads, num_envs),
                                               autoreset_mode);
}

}  // namespace upkie_rl
