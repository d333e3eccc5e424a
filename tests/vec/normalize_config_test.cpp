#include "vec/normalize_config.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/option_table.hpp"
#include "vec/normalization_state.hpp"

namespace upkie_rl {
namespace {

std::string error_of(const nlohmann::json& json) {
  try {
    normalize_config_from_json(json);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(NormalizeConfig, DefaultsWriteTheWireTextOfEveryCheckpoint) {
  EXPECT_EQ(normalize_config_to_json(NormalizeConfig{}).dump(),
            R"({"clip_observations":10.0,"clip_rewards":10.0,"epsilon":1e-08,"gamma":0.99,)"
            R"("observations":true,"rewards":true})");
}

TEST(NormalizeConfig, JsonRoundTripIsExact) {
  NormalizeConfig config;
  config.observations = false;
  config.rewards = true;
  config.clip_observations = 1.0 / 3.0;
  config.clip_rewards = 123456.789;
  config.gamma = 0.999999999999;
  config.epsilon = 3e-300;
  const NormalizeConfig read = normalize_config_from_json(normalize_config_to_json(config));
  EXPECT_EQ(read.observations, config.observations);
  EXPECT_EQ(read.rewards, config.rewards);
  EXPECT_EQ(read.clip_observations, config.clip_observations);
  EXPECT_EQ(read.clip_rewards, config.clip_rewards);
  EXPECT_EQ(read.gamma, config.gamma);
  EXPECT_EQ(read.epsilon, config.epsilon);
}

TEST(NormalizeConfig, ReadingNamesTheMissingMistypedOrOutOfRangeKey) {
  const nlohmann::json good = normalize_config_to_json(NormalizeConfig{});
  nlohmann::json missing = good;
  missing.erase("rewards");
  EXPECT_EQ(error_of(missing), "config.rewards must be a boolean");
  nlohmann::json mistyped = good;
  mistyped["clip_rewards"] = "10";
  EXPECT_EQ(error_of(mistyped), "config.clip_rewards must be a number");
  nlohmann::json integer = good;
  integer["clip_rewards"] = 3;  // JSON integers are numbers too.
  EXPECT_EQ(normalize_config_from_json(integer).clip_rewards, 3.0);
  nlohmann::json out_of_range = good;
  out_of_range["gamma"] = 0.0;
  EXPECT_EQ(error_of(out_of_range), "normalization gamma: 0 is outside (0, 1]");
  EXPECT_EQ(error_of(nlohmann::json::array()), "config must be an object");
}

TEST(NormalizeConfig, CheckRefusesEachBound) {
  NormalizeConfig config;
  EXPECT_NO_THROW(check_normalize_config(config));
  config.clip_observations = 2e6;
  EXPECT_THROW(check_normalize_config(config), std::invalid_argument);
  config = {};
  config.epsilon = 0.0;
  EXPECT_THROW(check_normalize_config(config), std::invalid_argument);
}

// The training configuration's keys are the state's, with its prefix, in the same order.
TEST(NormalizeConfig, OneDeclarationForTheTrainingKeysAndTheState) {
  NormalizeConfig config;
  OptionTable table;
  config.declare_options(table, "normalize.");
  const std::vector<std::string> expected = {
      std::string("normalize.") + normalization_state::kObservations,
      std::string("normalize.") + normalization_state::kRewards,
      std::string("normalize.") + normalization_state::kClipObservations,
      std::string("normalize.") + normalization_state::kClipRewards,
      std::string("normalize.") + normalization_state::kGamma,
      std::string("normalize.") + normalization_state::kEpsilon};
  EXPECT_EQ(table.names(), expected);
  table.apply({{"normalize.gamma", "0.9"}, {"normalize.rewards", "false"}}, "test");
  EXPECT_EQ(config.gamma, 0.9);
  EXPECT_FALSE(config.rewards);
  EXPECT_EQ(normalize_config_to_json(config).at("gamma"), 0.9);
}

}  // namespace
}  // namespace upkie_rl
