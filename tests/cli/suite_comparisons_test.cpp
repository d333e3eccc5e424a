// The suite's comparisons from constructed results, without running an episode: the worlds
// where a contender falls and the other stands, and those where it falls more often beyond
// chance, with their counts and p-values in the table and the JSON.

#include <gtest/gtest.h>

#include <string>

#include "cli/suite_evaluation.hpp"

namespace upkie_rl::apps {
namespace {

CellResult cell(int falls, int episodes) {
  CellResult result;
  result.summary.episodes = episodes;
  result.successes = episodes - falls;
  return result;
}

// Two contenders over three worlds of 20 episodes: a falls once where b stands (p 0.5, not
// told apart), b falls 15 times where a falls once (p < 0.001), both stand in the third.
SuiteResults three_worlds() {
  SuiteResults run;
  run.suite.name = "three";
  run.suite.episodes = 20;
  for (const char* name : {"pushes", "payload", "nominal"}) {
    run.suite.worlds.push_back({name, "Upkie-MuJoCo-Velocity", {}, 0});
  }
  run.labels = {"a", "b"};
  run.descriptions = {"model", "controller"};
  run.results = {
      {cell(1, 20), cell(0, 20)}, {cell(1, 20), cell(15, 20)}, {cell(0, 20), cell(0, 20)}};
  return run;
}

TEST(SuiteComparisons, TheTableSaysWhichFallsAreToldApartFromChance) {
  const std::string table = suite_table(three_worlds());
  EXPECT_NE(table.find("a falls where b stands: 1 world(s): pushes (MuJoCo) 1/20 against 0/20, "
                       "p 0.500\n"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("a falls more often than b (one-sided Fisher exact test, p < 0.05): 0 "
                       "world(s)\n"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("b falls where a stands: 0 world(s)\n"), std::string::npos) << table;
  EXPECT_NE(table.find("b falls more often than a (one-sided Fisher exact test, p < 0.05): 1 "
                       "world(s): payload (MuJoCo) 15/20 against 1/20, p < 0.001\n"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("from 20 episodes a world's falls bound its fall rate (one-sided 95 % "
                       "confidence): 0 -> 13.9 %, 1 -> 21.6 %, 2 -> 28.3 %, 3 -> 34.4 %\n"),
            std::string::npos)
      << table;
}

TEST(SuiteComparisons, TheJsonListsTheWorldsWithTheirPValues) {
  const nlohmann::json json = suite_json(three_worlds());
  ASSERT_EQ(json["comparisons"].size(), 2u);
  const nlohmann::json& a_against_b = json["comparisons"][0];
  EXPECT_EQ(a_against_b["contender"], "a");
  ASSERT_EQ(a_against_b["falls_where_other_stands"].size(), 1u);
  EXPECT_EQ(a_against_b["falls_where_other_stands"][0]["world"], "pushes (MuJoCo)");
  EXPECT_NEAR(a_against_b["falls_where_other_stands"][0]["p_value"].get<double>(), 0.5, 1e-12);
  EXPECT_TRUE(a_against_b["falls_more_often"].empty());
  const nlohmann::json& b_against_a = json["comparisons"][1];
  ASSERT_EQ(b_against_a["falls_more_often"].size(), 1u);
  EXPECT_EQ(b_against_a["falls_more_often"][0]["world"], "payload (MuJoCo)");
  EXPECT_LT(b_against_a["falls_more_often"][0]["p_value"].get<double>(), 1e-3);
  EXPECT_NEAR(json["worlds"][2]["results"]["a"]["fall_rate_upper_95"].get<double>(), 0.1391, 1e-4);
}

}  // namespace
}  // namespace upkie_rl::apps
