#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "apps/cli_runner.hpp"

namespace upkie_rl {
namespace {

using testing::run_cli;

nlohmann::json last_line_json(const testing::CliResult& result) {
  const std::vector<std::string> lines = result.lines();
  if (lines.empty()) return nullptr;
  return nlohmann::json::parse(lines.back());
}

TEST(RolloutCommand, LinearControllerBalancesThePendulumForTheWholeEpisode) {
  const auto result = run_cli(
      "rollout --env Upkie-Bullet-Pendulum --controller linear:10,1,0,0.1 --episodes 2 "
      "--seed 0 --json");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = last_line_json(result);
  EXPECT_EQ(summary["episodes"], 2);
  EXPECT_EQ(summary["lengths"], nlohmann::json({300, 300}));
  EXPECT_DOUBLE_EQ(summary["mean_length"].get<double>(), 300.0);
  EXPECT_GT(summary["mean_return"].get<double>(), 250.0);
  EXPECT_LE(summary["mean_return"].get<double>(), 300.0);
  EXPECT_NE(result.output.find("episode 1: return"), std::string::npos);
  EXPECT_NE(result.output.find("(truncated)"), std::string::npos);
}

TEST(RolloutCommand, ZeroControllerFallsAndPyBulletAliasWorks) {
  const auto result =
      run_cli("rollout --env Upkie-PyBullet-Pendulum --controller zero --episodes 1 --json");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = last_line_json(result);
  EXPECT_LT(summary["lengths"][0].get<int>(), 300);
  EXPECT_NE(result.output.find("(terminated)"), std::string::npos);
  // One episode: its return is the mean and the std is zero.
  EXPECT_DOUBLE_EQ(summary["std_return"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(summary["returns"][0].get<double>(), summary["mean_return"].get<double>());
}

TEST(RolloutCommand, RecordsOneCsvRowPerStep) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "upkie_rl_rollout_record_test.csv";
  const auto result = run_cli(
      "rollout --env Upkie-Bullet-Pendulum --controller linear:10,1,0,0.1 --episodes 2 "
      "--max-steps 20 --record " +
      path.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::ifstream file(path);
  std::string header;
  std::getline(file, header);
  EXPECT_EQ(header,
            "episode,step,t,theta,p,theta_dot,p_dot,action.ground_velocity,reward,terminated,"
            "truncated,base_x,base_y,base_z,base_qw,base_qx,base_qy,base_qz,left_hip,left_knee,"
            "left_wheel,right_hip,right_knee,right_wheel,pitch,ground_position");
  int rows = 0;
  std::string line, last;
  while (std::getline(file, line)) {
    ++rows;
    last = line;
  }
  EXPECT_EQ(rows, 40);
  EXPECT_EQ(last.rfind("1,19,0.095", 0), 0u) << last;  // episode 1, step 19, t = 19 x 5 ms
  std::filesystem::remove(path);
}

TEST(RolloutCommand, ServosEnvWithTheNeutralAction) {
  const auto result =
      run_cli("rollout --env Upkie-Mock-Servos --controller zero --max-steps 10 --json");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = last_line_json(result);
  EXPECT_EQ(summary["lengths"][0], 10);
  EXPECT_DOUBLE_EQ(summary["mean_return"].get<double>(), 0.0);
}

TEST(RolloutCommand, InfoPrintsTheObservationDictionary) {
  const auto result = run_cli("rollout --env Upkie-Bullet-Gyropod --max-steps 5 --info --json");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::string info;
  for (const std::string& line : result.lines()) {
    if (line.rfind("info: ", 0) == 0) info = line.substr(6);
  }
  ASSERT_FALSE(info.empty()) << result.output;
  const nlohmann::json dictionary = nlohmann::json::parse(info);
  EXPECT_TRUE(dictionary["servo"]["left_wheel"].contains("velocity")) << info;
  EXPECT_TRUE(dictionary["base_orientation"].contains("pitch")) << info;
  EXPECT_EQ(last_line_json(result)["lengths"][0], 5);
}

TEST(RolloutCommand, BadInputGivesClearErrors) {
  auto unwritable =
      run_cli("rollout --env Upkie-Bullet-Pendulum --record /nonexistent-dir/record.csv");
  EXPECT_EQ(unwritable.exit_code, 1);
  EXPECT_NE(unwritable.output.find("cannot write the record file /nonexistent-dir/record.csv"),
            std::string::npos)
      << unwritable.output;
  EXPECT_EQ(unwritable.output.find("episode 0"), std::string::npos);  // refused before the run

  auto unknown_env = run_cli("rollout --env Upkie-Bullet-Walker");
  EXPECT_EQ(unknown_env.exit_code, 1);
  EXPECT_NE(unknown_env.output.find("not found"), std::string::npos) << unknown_env.output;

  auto unknown_controller = run_cli("rollout --env Upkie-Mock-Pendulum --controller pid");
  EXPECT_EQ(unknown_controller.exit_code, 1);
  EXPECT_NE(unknown_controller.output.find("linear:k1,k2,k3,k4"), std::string::npos);

  auto bad_gains = run_cli("rollout --env Upkie-Mock-Pendulum --controller linear:1,2,x,4");
  EXPECT_EQ(bad_gains.exit_code, 1);
  EXPECT_NE(bad_gains.output.find("four finite gains"), std::string::npos) << bad_gains.output;

  auto linear_on_servos = run_cli("rollout --env Upkie-Mock-Servos --controller linear:1,1,1,1");
  EXPECT_EQ(linear_on_servos.exit_code, 1);
  EXPECT_NE(linear_on_servos.output.find("\"theta\""), std::string::npos);

  auto bad_option = run_cli("rollout --env Upkie-Mock-Pendulum --env-option fall_pitch");
  EXPECT_EQ(bad_option.exit_code, 1);
  EXPECT_NE(bad_option.output.find("expected key=value"), std::string::npos);

  auto unknown_option = run_cli("rollout --env Upkie-Mock-Pendulum --env-option speed=3");
  EXPECT_EQ(unknown_option.exit_code, 1);
  EXPECT_NE(unknown_option.output.find("unknown option \"speed\""), std::string::npos);
}

}  // namespace
}  // namespace upkie_rl
