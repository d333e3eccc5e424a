// Fault injection (issue 26, item 1): every numeric setting is finite and bounded, checked
// before anything is allocated, with one line naming the key, the value and the limit.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rl/runs/training_config.hpp"

namespace upkie_rl {
namespace {

struct BadSetting {
  std::string override_text;  // key=value
  std::string value_shown;    // how the message shows the value
};

/// The message of the error validate() raises after `override_text`, or "" if none.
std::string validation_error(const std::string& override_text) {
  TrainingConfig config;
  try {
    apply_overrides(config, {override_text});
    config.validate();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(TrainingConfigBounds, EveryOutOfRangeOrNonFiniteSettingIsRefusedByName) {
  const std::vector<BadSetting> cases = {
      {"ppo.n_steps=2000000000000", "2000000000000"},
      {"policy.actor_hidden_sizes=[64, 300000]", "300000"},
      {"policy.critic_hidden_sizes=[400000]", "400000"},
      {"torch_threads=20000", "20000"},
      {"env.num_envs=3000000", "3000000"},
      {"env.threads=100000", "100000"},
      {"ppo.ent_coef=nan", "nan"},
      {"ppo.ent_coef=inf", "inf"},
      {"ppo.vf_coef=nan", "nan"},
      {"ppo.vf_coef=-inf", "-inf"},
      {"policy.log_std_init=nan", "nan"},
      {"policy.log_std_init=inf", "inf"},
      {"normalize.clip_rewards=1e39", "1e+39"},
      {"normalize.clip_observations=1e39", "1e+39"},
      {"ppo.clip_range=1e39", "1e+39"},
      {"normalize.epsilon=1e39", "1e+39"},
      {"ppo.learning_rate_initial=1e39", "1e+39"},
      {"ppo.learning_rate_final=nan", "nan"},
      {"ppo.clip_range_vf=inf", "inf"},
      {"ppo.max_grad_norm=inf", "inf"},
      {"ppo.gamma=nan", "nan"},
      {"ppo.gae_lambda=nan", "nan"},
      {"normalize.gamma=nan", "nan"},
      {"ppo.adam_eps=inf", "inf"},
      {"ppo.total_timesteps=9000000000000000000", "9000000000000000000"},
      {"checkpoint_every=9000000000000000000", "9000000000000000000"},
      {"env.curriculum_steps=9000000000000000000", "9000000000000000000"},
      {"ppo.n_epochs=100000000", "100000000"},
  };
  for (const BadSetting& bad : cases) {
    const std::string message = validation_error(bad.override_text);
    const std::string key = bad.override_text.substr(0, bad.override_text.find('='));
    ASSERT_FALSE(message.empty()) << bad.override_text << " was accepted";
    EXPECT_NE(message.find("'" + key + "'"), std::string::npos) << message;
    EXPECT_NE(message.find(bad.value_shown), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(TrainingConfigBounds, LimitsAreNamedInTheMessage) {
  EXPECT_EQ(validation_error("torch_threads=20000"),
            "config key 'torch_threads': 20000 is outside [1, 256]");
  EXPECT_EQ(validation_error("ppo.clip_range=1e39"),
            "config key 'ppo.clip_range': 1e+39 is outside (0, 100]");
  EXPECT_EQ(validation_error("ppo.ent_coef=nan"),
            "config key 'ppo.ent_coef': nan is not a finite number; expected one in [-1000, "
            "1000]");
}

TEST(TrainingConfigBounds, ValuesAtTheLimitsAreAccepted) {
  for (const char* good : {"torch_threads=256", "ppo.n_steps=1073741824", "normalize.epsilon=1",
                           "ppo.clip_range=100", "policy.log_std_init=-20", "ppo.ent_coef=-1000"}) {
    EXPECT_EQ(validation_error(good), "") << good;
  }
  TrainingConfig widest;
  apply_overrides(widest, {"env.num_envs=4096", "ppo.n_steps=4096"});
  EXPECT_NO_THROW(widest.validate());
}

TEST(TrainingConfigBounds, NetworkAndRolloutSizesAreCheckedAgainstTheirAllocation) {
  TrainingConfig config;
  config.policy.actor_hidden_sizes = {65536, 65536};
  config.validate();  // each width is allowed...
  try {
    config.check_allocations(4, 1);  // ...but not 2^32 parameters
    FAIL() << "a 2^32-parameter actor was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("policy.actor_hidden_sizes"), std::string::npos)
        << error.what();
    EXPECT_NE(std::string(error.what()).find("exceed the limit 67108864"), std::string::npos)
        << error.what();
  }
  TrainingConfig rollout;
  rollout.ppo.n_steps = std::int64_t{1} << 30;
  rollout.validate();
  // 2^30 transitions of a 60000-float observation: hundreds of terabytes.
  EXPECT_THROW(rollout.check_allocations(60000, 1), std::invalid_argument);
  TrainingConfig seed;
  EXPECT_NO_THROW(seed.check_allocations(4, 1));
}

}  // namespace
}  // namespace upkie_rl
