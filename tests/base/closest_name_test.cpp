/// The one "did you mean" of every refusal that lists valid names.

#include "base/closest_name.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace upkie_rl {
namespace {

TEST(ClosestName, EditDistanceCountsSwapsOnceAndIgnoresCase) {
  EXPECT_EQ(edit_distance("train", "train"), 0u);
  EXPECT_EQ(edit_distance("trian", "train"), 1u);  // one swap, not two substitutions
  EXPECT_EQ(edit_distance("Upkie-Mujoco-Pendulum", "Upkie-MuJoCo-Pendulum"), 0u);
  EXPECT_EQ(edit_distance("ppo.total_timestep", "ppo.total_timesteps"), 1u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
}

TEST(ClosestName, SuggestsOnlyANearName) {
  const std::vector<std::string> commands = {"envs", "rollout", "train", "view", "render"};
  EXPECT_EQ(closest_name("trian", commands), "train");
  EXPECT_EQ(closest_name("rolout", commands), "rollout");
  EXPECT_EQ(closest_name("xyzzy", commands), std::nullopt);
  EXPECT_EQ(closest_name("", commands), std::nullopt);
  // One letter is never rewritten into another name.
  EXPECT_EQ(closest_name("x", {"v"}), std::nullopt);
  EXPECT_EQ(closest_name("anything", {}), std::nullopt);
  // The first of equally near names.
  EXPECT_EQ(closest_name("bat", {"cat", "bag"}), "cat");
}

TEST(ClosestName, DidYouMeanIsEmptyWithoutANearName) {
  const std::vector<std::string> keys = {"ppo.total_timesteps", "ppo.n_steps"};
  EXPECT_EQ(did_you_mean("ppo.total_timestep", keys), " (did you mean \"ppo.total_timesteps\"?)");
  EXPECT_EQ(did_you_mean("seed", keys), "");
}

}  // namespace
}  // namespace upkie_rl
