/// `upkie-rl evaluate --suite` from the real binary: a small suite with the checked-in
/// velocity policy and the baseline writes every output with the same figures, falls
/// early in a world where nothing can stand, and a bad suite is refused before any episode.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/cli_runner.hpp"
#include "common/image_pixels.hpp"
#include "common/temp_files.hpp"

namespace upkie_rl {
namespace {

using testing::run_cli;
using testing::temp_path;

const std::string kVelocityPolicy =
    std::string(UPKIE_RL_TEST_DATA_DIR) + "/policies/velocity_mujoco_seed0.ckpt";

// Two worlds: the nominal one, and one whose motors are too weak to hold the robot up (a
// tenth of their torque): everything falls there, within the first second.
constexpr const char* kSuite = R"(name: tiny
description: two worlds
envs: [Upkie-MuJoCo-Velocity]
episodes: 2
seed: 3
max_steps: 100
early_fall_time: 1.0
options: {command_start_delay: 1.0}
worlds:
  - name: nominal
  - name: "no torque, \"really\""
    options: {torque_limit_scale: 0.1}
)";

std::filesystem::path write_suite(const std::string& name, const std::string& text) {
  const auto path = temp_path(name);
  std::ofstream(path) << text;
  return path;
}

std::string last_line(std::string text) {
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return text.substr(text.rfind('\n') + 1);
}

TEST(EvaluateSuite, TinySuiteWritesTheTableJsonCsvAndHeatMap) {
  const auto suite = write_suite("suite_tiny.yaml", kSuite);
  const auto output = temp_path("suite_tiny_out");
  std::filesystem::remove_all(output);
  const auto result =
      run_cli("evaluate --suite " + suite.string() + " --model policy=" + kVelocityPolicy +
              " --controller lqr --threads 2 --json --output " + output.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("suite tiny: two worlds"), std::string::npos) << result.output;
  // The episodes' start, said in the table and the summary.
  EXPECT_NE(result.output.find("seeds 3.. from random starts; falls"), std::string::npos)
      << result.output;
  const nlohmann::json summary = nlohmann::json::parse(last_line(result.output));
  EXPECT_EQ(summary["start"], "from random starts");
  ASSERT_EQ(summary["worlds"].size(), 2u);
  for (const char* label : {"policy", "lqr"}) {
    const auto& nominal = summary["worlds"][0]["results"][label];
    const auto& weak = summary["worlds"][1]["results"][label];
    EXPECT_EQ(nominal["episodes"], 2) << label;
    EXPECT_EQ(nominal["falls"], 0) << label;
    EXPECT_EQ(weak["falls"], 2) << label;
    EXPECT_EQ(weak["early_falls"], 2) << label;
    EXPECT_TRUE(nominal["tracking_rms_vx"].is_number()) << label;
    // No fall in 2 episodes leaves a fall rate up to 1 - 0.05^(1/2); all fell: up to 1.
    EXPECT_NEAR(nominal["fall_rate_upper_95"].get<double>(), 0.7764, 1e-4) << label;
    EXPECT_EQ(weak["fall_rate_upper_95"], 1.0) << label;
  }
  ASSERT_EQ(summary["comparisons"].size(), 2u);
  EXPECT_EQ(summary["comparisons"][0]["contender"], "policy");
  EXPECT_EQ(summary["comparisons"][0]["other"], "lqr");
  EXPECT_TRUE(summary["comparisons"][0]["falls_where_other_stands"].empty());
  EXPECT_NE(result.output.find("from 2 episodes a world's falls bound its fall rate (one-sided "
                               "95 % confidence): 0 -> 77.6 %, 1 -> 97.5 %, 2 -> 100.0 %"),
            std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("policy falls more often than lqr (one-sided Fisher exact test, "
                               "p < 0.05): 0 world(s)"),
            std::string::npos)
      << result.output;
  EXPECT_EQ(summary["worlds"][1]["options"]["torque_limit_scale"], "0.1");
  EXPECT_NE(result.output.find("2/2 (2 early)"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("policy: 2 falls (2 early) in 1 of 2 worlds"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("policy falls where lqr stands: 0 world(s)"), std::string::npos)
      << result.output;
  std::ifstream csv(output / "results.csv");
  std::string header, row;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("world,env,contender,episodes,falls,early_falls,", 0), 0u) << header;
  EXPECT_EQ(header.substr(header.rfind(',') + 1), "fall_rate_upper_95") << header;
  int rows = 0;
  bool quoted = false;
  while (std::getline(csv, row)) {
    ++rows;
    quoted |= row.rfind(R"("no torque, ""really""",Upkie-MuJoCo-Velocity,policy,2,2,2,)", 0) == 0;
  }
  EXPECT_EQ(rows, 4);
  EXPECT_TRUE(quoted);
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(output / "summary.json")), summary);
  std::ifstream table(output / "table.txt");
  std::stringstream table_text;
  table_text << table.rdbuf();
  EXPECT_NE(result.output.find(table_text.str()), std::string::npos);
  // Green where no episode fell (the nominal world), red where all did; a cell is about
  // 250 x 200 pixels.
  EXPECT_GT(testing::count_pixels_near(output / "falls.png", 0x1a9850), 20000);
  EXPECT_GT(testing::count_pixels_near(output / "falls.png", 0xd73027), 20000);
  std::filesystem::remove_all(output);
}

// --env-option goes after the suite's options and before a world's: here the suite's
// motors are too weak to stand (a tenth of their torque), the command line gives them back
// their torque, and a world's own weak motors stay weak.
TEST(EvaluateSuite, EnvOptionsChangeTheSuitesOptionsButNotAWorlds) {
  const auto suite = write_suite("suite_weak.yaml", R"(name: weak
description: weak motors unless told
envs: [Upkie-MuJoCo-Velocity]
episodes: 2
seed: 3
max_steps: 100
options: {torque_limit_scale: 0.1}
worlds:
  - name: the suite's motors
  - name: its own weak motors
    options: {torque_limit_scale: 0.1}
)");
  const std::string command = "evaluate --suite " + suite.string() + " --controller lqr --json";
  for (const bool given : {false, true}) {
    const auto result =
        run_cli(command + (given ? " --env-option torque_limit_scale=1" : std::string()));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const nlohmann::json summary = nlohmann::json::parse(last_line(result.output));
    EXPECT_EQ(summary["worlds"][0]["results"]["lqr"]["falls"], given ? 0 : 2) << result.output;
    EXPECT_EQ(summary["worlds"][1]["results"]["lqr"]["falls"], 2) << result.output;
  }
}

// A suite's duration is seconds for every contender: the baseline at 100 Hz runs twice the
// steps it runs at 50 Hz, and the policy runs past its training's time limit (it carries
// max_episode_steps 500); --max-steps makes it steps again.
TEST(EvaluateSuite, ADurationIsTheSameSecondsAtAnyRate) {
  const auto suite = write_suite("suite_seconds.yaml", R"(name: seconds
envs: [Upkie-MuJoCo-Velocity]
episodes: 1
seed: 3
duration: 12
worlds:
  - name: nominal
)");
  const std::string command = "evaluate --suite " + suite.string() + " --json";
  const auto run = [&](const std::string& extra) {
    const auto result = run_cli(command + extra);
    EXPECT_EQ(result.exit_code, 0) << result.output;
    return nlohmann::json::parse(last_line(result.output));
  };
  const auto length = [](const nlohmann::json& summary, const char* label) {
    EXPECT_EQ(summary["worlds"][0]["results"][label]["falls"], 0) << label;
    return summary["worlds"][0]["results"][label]["mean_length"].get<double>();
  };
  const nlohmann::json at_50_hz = run(" --controller lqr --model policy=" + kVelocityPolicy);
  EXPECT_EQ(length(at_50_hz, "lqr"), 600.0);
  EXPECT_EQ(length(at_50_hz, "policy"), 600.0);
  EXPECT_EQ(at_50_hz["duration"], 12.0);
  EXPECT_TRUE(at_50_hz["max_steps"].is_null());
  EXPECT_EQ(length(run(" --controller lqr --env-option frequency=100"), "lqr"), 1200.0);
  const nlohmann::json stepped = run(" --controller lqr --env-option frequency=100 --max-steps 40");
  EXPECT_EQ(length(stepped, "lqr"), 40.0);
  EXPECT_TRUE(stepped["duration"].is_null());
  EXPECT_EQ(stepped["max_steps"], 40);
}

TEST(EvaluateSuite, BadSuitesAreRefusedNamingTheWorldAndTheKey) {
  const auto expect_error = [](const std::string& text, const std::string& part) {
    const auto suite = write_suite("suite_bad.yaml", text);
    const auto result = run_cli("evaluate --suite " + suite.string() + " --controller lqr");
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find(part), std::string::npos) << result.output;
    EXPECT_EQ(result.output.find("falls"), std::string::npos) << result.output;  // nothing ran
  };
  std::string text = kSuite;
  expect_error(text.replace(text.find("torque_limit_scale"), 18, "torque_limit_scal"),
               "world \"no torque, \"really\"\" on Upkie-MuJoCo-Velocity: ");
  text = kSuite;
  expect_error(text.replace(text.find("0.1}"), 3, "-5"), "torque_limit_scale");
  expect_error(std::string(kSuite) + "bogus: 1\n", "unknown key \"bogus\"");
  const auto missing = run_cli("evaluate --suite no_such_suite --controller lqr");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.output.find("suite no_such_suite not found"), std::string::npos)
      << missing.output;
  const auto both =
      run_cli("evaluate --suite reality --env Upkie-MuJoCo-Velocity --controller lqr");
  EXPECT_EQ(both.exit_code, 1);
  EXPECT_NE(both.output.find("without --env and --grid"), std::string::npos) << both.output;
}

}  // namespace
}  // namespace upkie_rl
