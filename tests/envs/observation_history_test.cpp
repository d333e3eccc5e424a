/// The observation_history option (ObservationHistory): 1 is today's environment bit for
/// bit; k > 1 shows the last k observations newest first, the noisy ones the agent saw,
/// filled with the reset's at reset; its space repeats the inner one; bad lengths are refused
/// naming the option; it is a task option that rollouts and the runner carry.

#include "envs/wrappers/observation_history.hpp"
#include "common/velocity_baseline.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/error_message.hpp"
#include "envs/registry/env_factory.hpp"
#include "envs/registry/registry.hpp"

namespace upkie_rl {
namespace {

constexpr const char* kVelocity = "Upkie-MuJoCo-Velocity";

/// The velocity task as configs/velocity.yaml trains it, in short: residual on the
/// baseline, observation noise, action lag and IMU noise on, pushes often.
EnvOptions trained_options(const std::string& history) {
  return {{"nb_substeps", "10"},
          {"height_command", "false"},
          {"leg_action_scale", "0.5"},
          {"base_controller", testing::kVelocityBaseline},
          {"residual_scale", "0.3"},
          {"observation_noise", "0.005"},
          {"imu_gyroscope_noise", "0.01"},
          {"action_lag_max", "0.08"},
          {"push_force", "30"},
          {"push_interval", "0.5"},
          {"observation_history", history}};
}

/// Observations and rewards of `steps` steps from reset(seed), with actions that depend on
/// the step only (so that every history length sees the same inner trajectory).
struct Trace {
  std::vector<std::vector<float>> observations;
  std::vector<double> rewards;
};

Trace run(Env& env, std::uint64_t seed, int steps) {
  Trace trace;
  std::vector<float> observation(env.observation_space().size());
  std::vector<float> action(env.action_space().size());
  env.reset(seed, observation);
  trace.observations.push_back(observation);
  for (int step = 0; step < steps; ++step) {
    for (std::size_t i = 0; i < action.size(); ++i) {
      action[i] = 0.5f * std::sin(0.1f * static_cast<float>(step) + static_cast<float>(i));
    }
    const StepResult result = env.step(action, observation);
    trace.observations.push_back(observation);
    trace.rewards.push_back(result.reward);
    if (result.terminated || result.truncated) break;
  }
  return trace;
}

using testing::error_message;

TEST(ObservationHistory, LengthOneIsTodaysEnvironmentBitForBit) {
  EnvOptions today = trained_options("1");
  today.pop_back();
  auto plain = make_env(kVelocity, today);
  auto one = make_env(kVelocity, trained_options("1"));
  EXPECT_EQ(one->observation_space().names, plain->observation_space().names);
  const Trace expected = run(*plain, 7, 120);
  const Trace actual = run(*one, 7, 120);
  EXPECT_EQ(actual.observations, expected.observations);
  EXPECT_EQ(actual.rewards, expected.rewards);
  EXPECT_EQ(actual.rewards.size(), 120u);
}

TEST(ObservationHistory, ShowsTheNoisyObservationsTheAgentSawNewestFirst) {
  auto plain = make_env(kVelocity, trained_options("1"));
  auto stacked = make_env(kVelocity, trained_options("3"));
  const std::size_t size = plain->observation_space().size();
  ASSERT_EQ(stacked->observation_space().size(), 3 * size);
  const Trace seen = run(*plain, 11, 60);
  const Trace history = run(*stacked, 11, 60);
  ASSERT_EQ(history.observations.size(), seen.observations.size());
  // The rewards come from the same trajectory: the base controller and the task read the
  // inner observation, not the history.
  EXPECT_EQ(history.rewards, seen.rewards);
  for (std::size_t t = 0; t < seen.observations.size(); ++t) {
    for (std::size_t age = 0; age < 3; ++age) {
      // At reset, and for the first steps, the missing past is the reset observation.
      const std::size_t source = t >= age ? t - age : 0;
      const std::vector<float>& expected = seen.observations[source];
      const auto block = history.observations[t].begin() + static_cast<std::ptrdiff_t>(age * size);
      // Bit for bit, noise included: the history keeps each step's noisy observation
      // (outside the noise wrapper), it does not draw fresh noise on old ones.
      EXPECT_TRUE(std::equal(expected.begin(), expected.end(), block))
          << "step " << t << ", age " << age;
    }
  }
  // The observations differ from step to step (the test would pass on constants).
  EXPECT_NE(seen.observations[5], seen.observations[6]);
}

TEST(ObservationHistory, SpaceRepeatsTheInnerBoundsAndNamesTheAges) {
  auto plain = make_env(kVelocity, trained_options("1"));
  auto stacked = make_env(kVelocity, trained_options("3"));
  const BoxSpace& inner = plain->observation_space();
  const BoxSpace& space = stacked->observation_space();
  const std::size_t size = inner.size();
  ASSERT_EQ(space.size(), 3 * size);
  ASSERT_EQ(space.names.size(), 3 * size);
  for (std::size_t i = 0; i < size; ++i) {
    EXPECT_EQ(space.names[i], inner.names[i]);
    EXPECT_EQ(space.names[size + i], inner.names[i] + "@t-1");
    EXPECT_EQ(space.names[2 * size + i], inner.names[i] + "@t-2");
    for (std::size_t age = 0; age < 3; ++age) {
      EXPECT_EQ(space.low[age * size + i], inner.low[i]);
      EXPECT_EQ(space.high[age * size + i], inner.high[i]);
    }
  }
  EXPECT_LT(space.index_of("gyro.y@t-1"), space.size());
  EXPECT_EQ(space.index_of("gyro.y"), inner.index_of("gyro.y"));
  EXPECT_EQ(stacked->action_space().size(), plain->action_space().size());
}

TEST(ObservationHistory, BadLengthsAreRefusedNamingTheOption) {
  for (const char* bad : {"0", "-1", "1000000", "1e6", "2.5", "three"}) {
    const std::string message = error_message([bad] {
      make_env("Upkie-Mock-Pendulum", {{"observation_history", bad}});
    });
    EXPECT_NE(message.find("observation_history"), std::string::npos) << bad << ": " << message;
  }
  const std::string direct =
      error_message([] { ObservationHistory history(make_env("Upkie-Mock-Pendulum"), 0); });
  EXPECT_NE(direct.find("observation_history"), std::string::npos) << direct;
  EXPECT_NO_THROW(make_env("Upkie-Mock-Pendulum",
                           {{"observation_history", std::to_string(kMaxObservationHistory)}}));
}

TEST(ObservationHistory, WrongObservationSizeIsRefused) {
  ObservationHistory history(make_env("Upkie-Mock-Pendulum"), 2);
  std::vector<float> inner_sized(history.inner().observation_space().size());
  EXPECT_THROW(history.reset(0, inner_sized), std::invalid_argument);
}

TEST(ObservationHistory, IsATaskOptionCarriedToTheSpine) {
  const EnvOptions trained = {{"observation_history", "3"}, {"observation_noise", "0.01"}};
  const EnvOptions kept = task_options(kVelocity, trained, "Upkie-Spine-Velocity");
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0].first, "observation_history");
  EXPECT_EQ(kept[0].second, "3");
  for (const OptionInfo& info : env_option_info("Upkie-Spine-Velocity")) {
    if (info.name == "observation_history") EXPECT_FALSE(info.randomization);
  }
}

}  // namespace
}  // namespace upkie_rl
