// make_mixed_vector_env: two engines of one task in one vector environment (training's
// env.mix_id), spread evenly, each environment stepping as the single environment of its id.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "envs/registry/env_factory.hpp"
#include "vec/make_vector_env.hpp"

namespace upkie_rl {
namespace {

constexpr const char* kMuJoCo = "Upkie-MuJoCo-Pendulum";
constexpr const char* kBullet = "Upkie-Bullet-Pendulum";

TEST(MixedVectorEnv, SpreadsTheMixedEnvironmentsEvenly) {
  std::vector<std::size_t> mixed;
  for (std::size_t i = 0; i < 16; ++i) {
    if (is_mixed_env(i, 4, 16)) mixed.push_back(i);
  }
  EXPECT_EQ(mixed, (std::vector<std::size_t>{3, 7, 11, 15}));
  for (std::size_t count = 0; count < 7; ++count) {
    std::size_t total = 0;
    for (std::size_t i = 0; i < 7; ++i) total += is_mixed_env(i, count, 7) ? 1 : 0;
    EXPECT_EQ(total, count);
  }
}

/// The observations of `id` alone after a reset with `seed` and `steps` steps of `action`.
std::vector<float> single_env_observation(const std::string& id, std::uint64_t seed, int steps,
                                          float action) {
  auto env = make_env(id, {});
  std::vector<float> observation(env->observation_space().size());
  env->reset(seed, observation);
  const std::vector<float> actions = {action};
  for (int step = 0; step < steps; ++step) env->step(actions, observation);
  return observation;
}

TEST(MixedVectorEnv, EachEnvironmentStepsAsItsOwnEngine) {
  auto venv = make_mixed_vector_env(kMuJoCo, kBullet, 1, {}, 3, 2);
  venv->reset(40);
  const std::vector<float> actions = {0.2f, 0.2f, 0.2f};
  VectorStep step;
  for (int i = 0; i < 5; ++i) step = venv->step(actions);
  const std::size_t size = venv->observation_space().size();
  // Environment 2 of 3 is the one of Bullet (is_mixed_env(2, 1, 3)); env i is seeded 40 + i.
  for (std::size_t i = 0; i < 3; ++i) {
    const std::string id = i == 2 ? kBullet : kMuJoCo;
    const std::string other = i == 2 ? kMuJoCo : kBullet;
    const std::vector<float> got(step.observations.begin() + static_cast<long>(i * size),
                                 step.observations.begin() + static_cast<long>((i + 1) * size));
    EXPECT_EQ(got, single_env_observation(id, 40 + i, 5, 0.2f)) << "env " << i;
    EXPECT_NE(got, single_env_observation(other, 40 + i, 5, 0.2f)) << "env " << i;
  }
}

TEST(MixedVectorEnv, RefusesTasksWhoseSpacesDifferNamingBoth) {
  try {
    make_mixed_vector_env(kMuJoCo, "Upkie-MuJoCo-Velocity", 1, {}, 2, 0);
    FAIL() << "a pendulum and a velocity task were mixed";
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(kMuJoCo), std::string::npos) << message;
    EXPECT_NE(message.find("Upkie-MuJoCo-Velocity"), std::string::npos) << message;
  }
  EXPECT_THROW(make_mixed_vector_env(kMuJoCo, kBullet, 2, {}, 2, 0), std::invalid_argument);
}

}  // namespace
}  // namespace upkie_rl
