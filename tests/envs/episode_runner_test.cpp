/// Whole episodes with a controller, and their summary.

#include "envs/evaluation/episode_runner.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "envs/controllers/builtin_controllers.hpp"
#include "envs/registry/env_factory.hpp"

namespace upkie_rl {
namespace {

TEST(EpisodeRunner, AnEpisodeEndsAtTheEnvsEndOrAtMaxSteps) {
  std::unique_ptr<Env> env = make_env("Upkie-Bullet-Pendulum", {});
  ZeroController zero(*env);
  std::vector<float> observation(env->observation_space().size());
  std::vector<float> action(env->action_space().size());
  // With no action the pendulum falls before its 300-step time limit.
  const EpisodeOutcome fall = run_episode(*env, zero, 0, 1000, observation, action);
  EXPECT_TRUE(fall.terminated);
  EXPECT_GT(fall.length, 1);
  EXPECT_LT(fall.length, 300);
  const EpisodeOutcome cut = run_episode(*env, zero, 0, 5, observation, action);
  EXPECT_FALSE(cut.terminated);
  EXPECT_EQ(cut.length, 5);
  EXPECT_GT(cut.total_reward, 0.0);  // upright: a positive reward per step
  EXPECT_NE(fall.total_reward, cut.total_reward);
  // The same seed gives the same episode.
  EXPECT_EQ(run_episode(*env, zero, 0, 1000, observation, action).total_reward, fall.total_reward);
}

TEST(EpisodeRunner, TheSummaryCountsSurvivalsAndTheSpreadOfReturns) {
  const EpisodeSummary summary =
      summarize_episodes({{1.0, 10, true}, {3.0, 20, false}, {5.0, 30, false}});
  EXPECT_EQ(summary.episodes, 3);
  EXPECT_EQ(summary.successes, 2);
  EXPECT_DOUBLE_EQ(summary.mean_return, 3.0);
  EXPECT_DOUBLE_EQ(summary.std_return, std::sqrt(8.0 / 3.0));
  EXPECT_DOUBLE_EQ(summary.mean_length, 20.0);
  EXPECT_EQ(summarize_episodes({}).episodes, 0);
}

}  // namespace
}  // namespace upkie_rl
