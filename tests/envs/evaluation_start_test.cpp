#include "envs/evaluation/evaluation_start.hpp"

#include <gtest/gtest.h>

namespace upkie_rl {
namespace {

// The words an evaluation prints follow the options its episodes had.
TEST(EvaluationStartWords, RandomWhenTheEvaluationsStartIsAdded) {
  const EnvOptions options = with_evaluation_start("Upkie-Bullet-Pendulum", {});
  ASSERT_FALSE(options.empty());
  EXPECT_EQ(evaluation_start_words("Upkie-Bullet-Pendulum", options, false), "from random starts");
}

TEST(EvaluationStartWords, ExactWhenAskedAndNothingRandomises) {
  EXPECT_EQ(evaluation_start_words("Upkie-Bullet-Pendulum", {}, true),
            "from the exact start (--exact-start)");
}

TEST(EvaluationStartWords, AUsersRandomisationIsRandomEvenWithExactStart) {
  const EnvOptions options = {{"init_rand_pitch", "0.1"}};
  EXPECT_EQ(evaluation_start_words("Upkie-Bullet-Pendulum", options, true), "from random starts");
}

TEST(EvaluationStartWords, TheLastValueGivenWins) {
  const EnvOptions options = {{"init_rand_pitch", "0.1"}, {"init_rand_pitch", "0"}};
  EXPECT_EQ(evaluation_start_words("Upkie-Bullet-Pendulum", options, true),
            "from the exact start (--exact-start)");
}

TEST(EvaluationStartWords, UnknownIdIsRefused) {
  EXPECT_THROW(evaluation_start_words("Upkie-Nowhere", {}, false), std::invalid_argument);
}

}  // namespace
}  // namespace upkie_rl
