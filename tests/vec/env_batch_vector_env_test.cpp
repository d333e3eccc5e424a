/// The forwarding shared by SyncVectorEnv and ThreadPoolVectorEnv (vec/env_batch_vector_env.hpp).

#include "vec/env_batch_vector_env.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>

#include "vec/make_vector_env.hpp"
#include "vec/sync_vector_env.hpp"
#include "vec/thread_pool_vector_env.hpp"

namespace upkie_rl {
namespace {

// Both kinds answer from their environments: the same spaces, terms and full observations.
TEST(EnvBatchVectorEnv, BothKindsForwardToTheirEnvironments) {
  for (const std::size_t threads : {0, 2}) {
    SCOPED_TRACE(threads);
    std::unique_ptr<VectorEnv> venv = make_vector_env("Upkie-Mock-Velocity", {}, 3, threads);
    if (threads == 0) {
      EXPECT_NE(dynamic_cast<SyncVectorEnv*>(venv.get()), nullptr);
    } else {
      EXPECT_NE(dynamic_cast<ThreadPoolVectorEnv*>(venv.get()), nullptr);
    }
    const auto* batch = dynamic_cast<const EnvBatchVectorEnv*>(venv.get());
    ASSERT_NE(batch, nullptr);
    venv->reset(7);
    EXPECT_EQ(venv->num_envs(), 3u);
    EXPECT_EQ(&venv->observation_space(), &batch->env(0).observation_space());
    EXPECT_EQ(&venv->action_space(), &batch->env(0).action_space());
    EXPECT_EQ(venv->reward_term_names().data(), batch->env(0).reward_term_names().data());
    EXPECT_EQ(venv->reward_term_names().size(), 12u);  // 5 + track_height, leg_symmetry,
                                                       // height_error, forward_velocity_error,
                                                       // tilt_excess, shin_tilt_excess,
                                                       // floor_tilt_excess
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(venv->full_observation(i), batch->env(i).full_observation());
    }
    // The scale reaches the environments, which check it.
    EXPECT_NO_THROW(venv->set_randomization_scale(0.5));
    EXPECT_THROW(venv->set_randomization_scale(2.0), std::invalid_argument);
  }
}

}  // namespace
}  // namespace upkie_rl
