#include "vec/make_vector_env.hpp"

#include <algorithm>
#include <stdexcept>

#include "model/setting_bounds.hpp"
#include "vec/sync_vector_env.hpp"
#include "vec/thread_pool_vector_env.hpp"

namespace upkie_rl {

std::unique_ptr<VectorEnv> make_vector_env(const std::string& id, const EnvOptions& options,
                                           std::size_t num_envs, std::size_t threads,
                                           AutoresetMode autoreset_mode) {
  // Python passes these unchecked; the configuration checked them already under its keys.
  check_setting("num_envs", static_cast<std::int64_t>(num_envs), 1,
                static_cast<std::int64_t>(kMaxVectorEnvs));
  check_setting("num_threads", static_cast<std::int64_t>(threads), 0,
                static_cast<std::int64_t>(kMaxEnvThreads));
  const EnvFactory factory = make_env_factory(id, options);
  std::vector<std::unique_ptr<Env>> envs;
  envs.reserve(num_envs);
  for (std::size_t i = 0; i < num_envs; ++i) envs.push_back(factory());
  if (threads == 0) return std::make_unique<SyncVectorEnv>(std::move(envs), autoreset_mode);
  return std::make_unique<ThreadPoolVectorEnv>(std::move(envs), std::min(threads, num_envs),
                                               autoreset_mode);
}

}  // namespace upkie_rl
