#include "vec/vec_normalize.hpp"

#include <gtest/gtest.h>

#include <array>

#include "vec/counting_env.hpp"
#include "vec/sync_vector_env.hpp"

namespace upkie_rl {
namespace {

std::unique_ptr<VecNormalize> make_normalized(int length = 10, NormalizeConfig config = {}) {
  std::vector<std::unique_ptr<Env>> envs;
  envs.push_back(std::make_unique<testing::CountingEnv>(length));
  envs.push_back(std::make_unique<testing::CountingEnv>(length));
  return std::make_unique<VecNormalize>(std::make_unique<SyncVectorEnv>(std::move(envs)), config);
}

// Expected values computed by hand with SB3's formulas (see the python of the report):
// reset observations (0, 0, 0) and (1, 0, 0); then actions (1, 3) give observations
// (0, 1, 1) and (1, 1, 3) and rewards (1, 3).
TEST(VecNormalize, HandComputedObservationsAndRewards) {
  auto venv = make_normalized();
  const std::span<const float> first = venv->reset(0);
  EXPECT_NEAR(first[0], -0.9998500087508123, 1e-6);
  EXPECT_NEAR(first[3], 0.9999499937516877, 1e-6);
  EXPECT_EQ(first[1], 0.0f);
  const std::array<float, 2> actions{1.0f, 3.0f};
  const VectorStep& step = venv->step(actions);
  const std::array<double, 6> expected{-0.9999249871902265,   0.9999749834395859,
                                       2.041181911479199e-05, 0.9999749834395861,
                                       0.9999749834395859,    1.633006764645958};
  for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(step.observations[k], expected[k], 1e-6) << k;
  EXPECT_NEAR(step.rewards[0], 0.9999000199952511, 1e-6);
  EXPECT_NEAR(step.rewards[1], 2.999700059985753, 1e-6);
  EXPECT_NEAR(venv->observation_statistics().mean()[2], 0.9999750006249845, 1e-12);
  EXPECT_NEAR(venv->observation_statistics().var()[2], 1.5000124990625394, 1e-12);
  // Second step: G = 0.99·G + r.
  const VectorStep& second = venv->step(actions);
  EXPECT_NEAR(second.rewards[0], 0.5375790935156468, 1e-6);
  EXPECT_NEAR(second.rewards[1], 1.6127372805469404, 1e-6);
  // Raw values are kept.
  EXPECT_EQ(venv->raw_rewards()[1], 3.0f);
  EXPECT_EQ(venv->raw_observations()[5], 3.0f);
  EXPECT_EQ(venv->raw_observations()[4], 2.0f);
}

TEST(VecNormalize, ClipsObservationsAndRewards) {
  NormalizeConfig config;
  config.clip_observations = 0.5;
  config.clip_rewards = 0.25;
  auto venv = make_normalized(10, config);
  const std::span<const float> first = venv->reset(0);
  EXPECT_FLOAT_EQ(first[0], -0.5f);
  EXPECT_FLOAT_EQ(first[3], 0.5f);
  const std::array<float, 2> actions{1.0f, 3.0f};
  const VectorStep& step = venv->step(actions);
  EXPECT_FLOAT_EQ(step.rewards[0], 0.25f);
  EXPECT_FLOAT_EQ(step.rewards[1], 0.25f);
}

TEST(VecNormalize, FrozenWhenNotTraining) {
  auto venv = make_normalized();
  venv->reset(0);
  const std::array<float, 2> actions{1.0f, 3.0f};
  venv->step(actions);
  const nlohmann::json before = venv->state();
  venv->set_training(false);
  EXPECT_FALSE(venv->training());
  const VectorStep& step = venv->step(actions);
  EXPECT_EQ(venv->state(), before);
  EXPECT_EQ(step.rewards[0], 1.0f);  // raw
  EXPECT_EQ(step.rewards[1], 3.0f);
  // Observations are still normalised, with the frozen statistics.
  std::array<float, 6> normalized{};
  venv->normalize_observations(venv->raw_observations(), normalized);
  for (std::size_t k = 0; k < 6; ++k) EXPECT_EQ(step.observations[k], normalized[k]);
}

TEST(VecNormalize, FinalObservationsAreNormalisedAndReturnsRaw) {
  auto venv = make_normalized(2);
  venv->reset(0);
  const std::array<float, 2> actions{1.0f, 3.0f};
  venv->step(actions);
  const VectorStep& step = venv->step(actions);
  ASSERT_EQ(step.terminated[0], 1);
  EXPECT_EQ(step.episode_returns[0], 2.0);
  EXPECT_EQ(step.episode_returns[1], 6.0);
  // Final raw observation of env 1 is (1, 2, 3).
  const std::array<float, 3> raw{1.0f, 2.0f, 3.0f};
  std::array<float, 3> normalized{};
  venv->normalize_observations(raw, normalized);
  for (std::size_t j = 0; j < 3; ++j) EXPECT_EQ(step.final_observations[3 + j], normalized[j]);
}

TEST(VecNormalize, StateRoundTripAndNamedErrors) {
  auto trained = make_normalized();
  trained->reset(0);
  const std::array<float, 2> actions{1.0f, 3.0f};
  trained->step(actions);
  auto restored = make_normalized();
  restored->load_state(trained->state());
  EXPECT_EQ(restored->state(), trained->state());
  EXPECT_EQ(restored->observation_statistics().mean(), trained->observation_statistics().mean());

  auto error_of = [&](nlohmann::json state) {
    try {
      restored->load_state(state);
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string();
  };
  nlohmann::json missing = trained->state();
  missing.erase("returns");
  EXPECT_NE(error_of(missing).find("returns"), std::string::npos);
  nlohmann::json wrong_size = trained->state();
  wrong_size["observations"]["var"] = {1.0, 1.0};
  EXPECT_NE(error_of(wrong_size).find("observations.var"), std::string::npos);
  nlohmann::json wrong_type = trained->state();
  wrong_type["config"]["gamma"] = "high";
  EXPECT_NE(error_of(wrong_type).find("config.gamma"), std::string::npos);
  // A failed load leaves the statistics as they were.
  EXPECT_EQ(restored->state(), trained->state());
}

}  // namespace
}  // namespace upkie_rl

namespace upkie_rl {
namespace {

// With a mirror, the statistics are those of each batch and its image: symmetric, so that
// normalising a mirrored observation gives the mirror of the normalised one.
TEST(VecNormalize, MirroredStatisticsAreSymmetric) {
  auto venv = make_normalized();
  EXPECT_THROW(venv->set_statistics_mirror(SignedPermutation({1, 0}, {true, true}, "test")),
               std::invalid_argument);
  const SignedPermutation mirror({1, 0, 2}, {true, true, false}, "observation");
  venv->set_statistics_mirror(mirror);
  auto plain = make_normalized();
  venv->reset(0);
  plain->reset(0);
  const std::array<float, 2> actions{1.0f, 3.0f};
  for (int step = 0; step < 4; ++step) {
    venv->step(actions);
    plain->step(actions);
  }
  const RunningMeanStd& statistics = venv->observation_statistics();
  EXPECT_NE(plain->observation_statistics().mean()[0], -plain->observation_statistics().mean()[1]);
  EXPECT_NEAR(statistics.mean()[0], -statistics.mean()[1], 1e-12);
  EXPECT_NEAR(statistics.var()[0], statistics.var()[1], 1e-12);
  // A component the mirror keeps has the same mean but for the initial count's weight.
  EXPECT_NEAR(statistics.mean()[2], plain->observation_statistics().mean()[2], 1e-4);
  const std::array<float, 3> raw{0.5f, 2.0f, 4.0f};
  std::array<float, 3> image{}, normalized{}, normalized_image{}, image_of_normalized{};
  mirror.apply(raw, image);
  venv->normalize_observations(image, normalized_image);
  venv->normalize_observations(raw, normalized);
  mirror.apply(normalized, image_of_normalized);
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_NEAR(normalized_image[k], image_of_normalized[k], 1e-6);
}

}  // namespace
}  // namespace upkie_rl
