#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "apps/cli_runner.hpp"

namespace upkie_rl {
namespace {

using testing::run_cli;

TEST(EnvsCommand, ListsIdsWithTheirSpaces) {
  const auto result = run_cli("envs");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  for (const char* id : {"Upkie-Bullet-Pendulum", "Upkie-Mock-Gyropod", "Upkie-Spine-Servos",
                         "Upkie-Bullet-ServosTask"}) {
    EXPECT_NE(result.output.find(id), std::string::npos) << id;
  }
  EXPECT_NE(result.output.find("Box(4: theta [-3.14159, 3.14159], p [-inf, inf]"),
            std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("left_hip: Box(6: position [-1.26, 1.26]"), std::string::npos);
  EXPECT_NE(result.output.find("PyBullet"), std::string::npos);
  const auto with_options = run_cli("envs --options");
  EXPECT_NE(with_options.output.find("max_ground_velocity: action bound a_max [m/s] (default 1)"),
            std::string::npos);
}

TEST(BenchCommand, ReportsStepsPerSecondAsJson) {
  const auto result =
      run_cli("bench --env Upkie-Bullet-Pendulum --num-envs 2 --threads 2 --steps 20 --json");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = nlohmann::json::parse(result.lines().back());
  EXPECT_GT(summary["env_steps_per_s"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(summary["physics_steps_per_s"].get<double>(),
                   5.0 * summary["env_steps_per_s"].get<double>());
  EXPECT_EQ(summary["num_envs"], 2);
  EXPECT_EQ(summary["threads"], 2);
}

TEST(BenchCommand, BadInput) {
  EXPECT_NE(run_cli("bench --env Upkie-Bullet-Pendulum --num-envs 0").exit_code, 0);
  const auto unknown = run_cli("bench --env Nope");
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_NE(unknown.output.find("not found"), std::string::npos);
}

}  // namespace
}  // namespace upkie_rl
