// Provenance: new models record this build and the date; old ones read "unknown" where they
// cannot say, and the rest comes from their configuration and counters.

#include <gtest/gtest.h>

#include <regex>

#include "policy/build_info.hpp"
#include "policy/checkpoint_file.hpp"
#include "policy/provenance.hpp"

namespace upkie_rl {
namespace {

TEST(Provenance, NewProvenanceRecordsThisBuildAndTheUtcDate) {
  const nlohmann::json provenance = new_provenance("test");
  EXPECT_EQ(provenance.at("upkie_rl_version"), upkie_rl_version());
  EXPECT_EQ(provenance.at("source"), "test");
  const std::string commit = provenance.at("git_commit");
  EXPECT_TRUE(std::regex_match(commit, std::regex("[0-9a-f]{40}(-dirty)?|unknown"))) << commit;
  const std::string date = provenance.at("date");
  EXPECT_TRUE(std::regex_match(date, std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)"))) << date;
}

TEST(Provenance, AModelWithoutProvenanceShowsUnknownAndItsConfiguration) {
  const CheckpointFile file = read_checkpoint_file(std::filesystem::path(UPKIE_RL_TEST_DATA_DIR) /
                                                   "policies" / "pendulum_bullet_seed0.ckpt");
  ASSERT_FALSE(file.header.contains("provenance"));
  const nlohmann::json provenance = model_provenance(file.header);
  EXPECT_EQ(provenance.at("git_commit"), kUnknownProvenance);
  EXPECT_EQ(provenance.at("date"), kUnknownProvenance);
  EXPECT_EQ(provenance.at("env_id"), "Upkie-Bullet-Pendulum");
  EXPECT_EQ(provenance.at("env_options").at("frequency"), "200");
  EXPECT_EQ(provenance.at("seed"), "0");
  EXPECT_GE(provenance.at("timesteps").get<std::int64_t>(), 1'000'000);
  const std::string text = format_provenance(provenance);
  EXPECT_NE(text.find("git_commit: unknown\n"), std::string::npos) << text;
  EXPECT_NE(text.find("config:\n  env:\n"), std::string::npos) << text;
}

TEST(Provenance, StoredEntriesWinAndAHeaderWithNothingIsAllUnknown) {
  nlohmann::json header = {{"provenance", {{"seed", 7}, {"source", "import"}}},
                           {"config", "env:\n  id: Upkie-Mock-Pendulum\nseed: 3\n"}};
  const nlohmann::json provenance = model_provenance(header);
  EXPECT_EQ(provenance.at("seed"), 7);
  EXPECT_EQ(provenance.at("source"), "import");
  EXPECT_EQ(provenance.at("env_id"), "Upkie-Mock-Pendulum");
  const nlohmann::json empty = model_provenance(nlohmann::json::object());
  for (const char* key : {"upkie_rl_version", "env_id", "seed", "timesteps", "config"}) {
    EXPECT_EQ(empty.at(key), kUnknownProvenance) << key;
  }
}

}  // namespace
}  // namespace upkie_rl
