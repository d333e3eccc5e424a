/// Vector envs sum each reward term over an episode, beside its return.

#include <gtest/gtest.h>

#include <numeric>
#include <vector>

#include "vec/make_vector_env.hpp"

namespace upkie_rl {
namespace {

TEST(VectorRewardTerms, EpisodeTermSumsAddUpToTheReturn) {
  auto venv = make_vector_env("Upkie-Mock-Velocity", {{"max_episode_steps", "30"}}, 2, 0);
  const std::size_t num_terms = venv->reward_term_names().size();
  ASSERT_EQ(num_terms, 12u);  // the velocity task's, with track_height, leg_symmetry,
                              // height_error, forward_velocity_error, tilt_excess,
                              // shin_tilt_excess, floor_tilt_excess
  std::vector<float> actions(2 * venv->action_space().size(), 0.3f);
  venv->reset(0);
  int ended = 0;
  for (int step = 0; step < 30; ++step) {
    const VectorStep& result = venv->step(actions);
    for (std::size_t i = 0; i < 2; ++i) {
      if (!result.truncated[i] && !result.terminated[i]) continue;
      ++ended;
      const double* terms = result.episode_reward_terms.data() + i * num_terms;
      EXPECT_NEAR(std::accumulate(terms, terms + num_terms, 0.0), result.episode_returns[i], 1e-9);
    }
  }
  EXPECT_EQ(ended, 2);
  // Environments without terms have none.
  EXPECT_TRUE(make_vector_env("Upkie-Mock-Pendulum", {}, 1, 0)->reward_term_names().empty());
}

}  // namespace
}  // namespace upkie_rl
