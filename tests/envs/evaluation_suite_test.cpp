// EvaluationSuite files: worlds expanded over the envs with the suite's options first, and
// every mistake an error that names the file, the world and the key.

#include "envs/evaluation/evaluation_suite.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "envs/registry/env_factory.hpp"

namespace upkie_rl {
namespace {

constexpr const char* kTwoWorlds = R"(
name: test
envs: [Upkie-MuJoCo-Velocity, Upkie-Bullet-Velocity]
episodes: 3
seed: 7
max_steps: 50
early_fall_time: 0.5
options: {command_start_delay: 1.0}
worlds:
  - name: nominal
  - name: slippery
    options: {floor_friction: 0.4}
)";

/// What the tool checks: each world's environment can be made.
void make_world_env(const SuiteWorld& world) { make_env_factory(world.env_id, world.options); }

/// The message of the std::invalid_argument that parsing `text` throws ("" if none).
std::string error_of(const std::string& text) {
  try {
    parse_evaluation_suite(text, "suite t.yaml", make_world_env);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(EvaluationSuite, WorldsExpandOverTheEnvsWithTheSuiteOptionsFirst) {
  const EvaluationSuite suite = parse_evaluation_suite(kTwoWorlds, "t", make_world_env);
  EXPECT_EQ(suite.name, "test");
  EXPECT_EQ(suite.episodes, 3);
  EXPECT_EQ(suite.seed, 7u);
  EXPECT_EQ(suite.max_steps, 50);
  EXPECT_DOUBLE_EQ(suite.early_fall_time, 0.5);
  ASSERT_EQ(suite.worlds.size(), 4u);
  EXPECT_EQ(suite.worlds[0].name, "nominal");
  EXPECT_EQ(suite.worlds[0].env_id, "Upkie-MuJoCo-Velocity");
  EXPECT_EQ(suite.worlds[1].env_id, "Upkie-Bullet-Velocity");
  EXPECT_EQ(suite.worlds[2].name, "slippery");
  const EnvOptions expected = {{"command_start_delay", "1.0"}, {"floor_friction", "0.4"}};
  EXPECT_EQ(suite.worlds[3].options, expected);
  EXPECT_EQ(suite.worlds[3].suite_option_count, 1u);
}

TEST(EvaluationSuite, MistakesNameTheWorldAndTheKey) {
  std::string text = kTwoWorlds;
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string changed = text;
    changed.replace(changed.find(from), from.size(), to);
    return error_of(changed);
  };
  std::string error = with("floor_friction: 0.4", "floor_fiction: 0.4");
  EXPECT_NE(error.find("world \"slippery\""), std::string::npos) << error;
  EXPECT_NE(error.find("floor_fiction"), std::string::npos) << error;
  error = with("floor_friction: 0.4", "floor_friction: -1");
  EXPECT_NE(error.find("world \"slippery\""), std::string::npos) << error;
  EXPECT_NE(error.find("floor_friction"), std::string::npos) << error;
  error = with("episodes: 3", "episodes: 0");
  EXPECT_NE(error.find("episodes must be in [1, "), std::string::npos) << error;
  error = with("episodes: 3", "episode: 3");
  EXPECT_NE(error.find("unknown key \"episode\""), std::string::npos) << error;
  error = with("  - name: slippery", "  - name: nominal");
  EXPECT_NE(error.find("world \"nominal\": another world has this name"), std::string::npos)
      << error;
  error = with("    options: {floor_friction: 0.4}", "    option: {floor_friction: 0.4}");
  EXPECT_NE(error.find("world 2: unknown key \"option\""), std::string::npos) << error;
  error = with("envs: [Upkie-MuJoCo-Velocity, Upkie-Bullet-Velocity]", "envs: Upkie");
  EXPECT_NE(error.find("envs must be a list"), std::string::npos) << error;
  error = with("envs: [Upkie-MuJoCo-Velocity, Upkie-Bullet-Velocity]", "envs: [Upkie-Nope]");
  EXPECT_NE(error.find("on Upkie-Nope"), std::string::npos) << error;
  EXPECT_NE(error_of("name: [unclosed").find("suite t.yaml: not YAML"), std::string::npos);
  EXPECT_NE(error_of("worlds: []\nname: x\nenvs: [Upkie-MuJoCo-Velocity]").find("non-empty list"),
            std::string::npos);
}

// An episode's length in seconds (the same seconds for contenders at any rate) or in
// steps, not both.
TEST(EvaluationSuite, AnEpisodeLastsSecondsOrSteps) {
  std::string text = kTwoWorlds;
  text.replace(text.find("max_steps: 50"), 13, "duration: 2.5");
  const EvaluationSuite suite = parse_evaluation_suite(text, "t", make_world_env);
  EXPECT_DOUBLE_EQ(suite.duration, 2.5);
  EXPECT_DOUBLE_EQ(parse_evaluation_suite(kTwoWorlds, "t", make_world_env).duration, 0.0);
  std::string error = error_of(std::string(kTwoWorlds) + "duration: 10\n");
  EXPECT_NE(error.find("give duration [s] or max_steps [agent steps], not both"), std::string::npos)
      << error;
  text.replace(text.find("duration: 2.5"), 13, "duration: 0.0");
  error = error_of(text);
  EXPECT_NE(error.find("duration must be in ["), std::string::npos) << error;
}

TEST(EvaluationSuite, TheShippedSuitesAreValid) {
  const std::filesystem::path directory =
      std::filesystem::path(UPKIE_RL_SOURCE_DIR) / "configs" / "suites";
  int suites = 0;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    const EvaluationSuite suite = read_evaluation_suite(entry.path(), make_world_env);
    EXPECT_FALSE(suite.worlds.empty()) << entry.path();
    ++suites;
  }
  EXPECT_GE(suites, 1);
  EXPECT_EQ(find_suite_file("reality", UPKIE_RL_SOURCE_DIR).filename(), "reality.yaml");
  EXPECT_THROW(find_suite_file("no_such_suite", UPKIE_RL_SOURCE_DIR), std::invalid_argument);
}

TEST(EvaluationSuite, RefusesAFileThatIsNotOne) {
  EXPECT_THROW(read_evaluation_suite("/dev/zero", make_world_env), std::invalid_argument);
  EXPECT_THROW(read_evaluation_suite("/nonexistent/suite.yaml", make_world_env),
               std::invalid_argument);
}

}  // namespace
}  // namespace upkie_rl
