/// One grammar for both tools, `upkie-rl` and `upkie-rl-agent` (issue 36, item 5): every
/// error is one line "<tool>: error: ..." with status 1, CLI11's own refusals included; a
/// mistyped command, environment id, configuration key or environment option gets the
/// nearest name suggested; the same flags for the same things in every command; --version on
/// both tools; every model format `info` reads either runs or is refused with what to run.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "apps/cli_runner.hpp"
#include "common/temp_files.hpp"

namespace upkie_rl {
namespace {

using testing::CliResult;
using testing::run_agent_cli;
using testing::run_cli;

const std::filesystem::path kPolicies = std::filesystem::path(UPKIE_RL_TEST_DATA_DIR) / "policies";
const std::string kPendulum = (kPolicies / "pendulum_bullet_seed0.ckpt").string();
/// The pendulum's training config, absolute: ctest runs the tests from the build directory.
const std::string kPendulumConfig = std::string(UPKIE_RL_SOURCE_DIR) + "/configs/pendulum.yaml";

/// `result` is a refusal: status 1 and one line, "<tool>: error: " then `message` somewhere.
void expect_one_line_error(const CliResult& result, const std::string& tool,
                           const std::string& message) {
  EXPECT_EQ(result.exit_code, 1) << result.output;
  ASSERT_EQ(result.lines().size(), 1u) << result.output;
  EXPECT_EQ(result.output.rfind(tool + ": error: ", 0), 0u) << result.output;
  EXPECT_NE(result.output.find(message), std::string::npos) << result.output;
}

/// The help text of `flag` in a command's help `help`: its line and those that continue it.
std::string flag_help(const CliResult& help, const std::string& flag) {
  std::string text;
  bool inside = false;
  for (const std::string& line : help.lines()) {
    const std::size_t first = line.find_first_not_of(' ');
    if (first != std::string::npos && line[first] == '-') inside = line.find(flag + " ") == first;
    if (inside) text += line + "\n";
  }
  return text;
}

/// The help text of `flag` in `command --help`.
std::string help_text(const std::string& command, const std::string& flag) {
  return flag_help(run_cli(command + " --help"), flag);
}

/// Every subcommand of `upkie-rl`, as its --help lists them.
std::vector<std::string> subcommands() {
  std::vector<std::string> names;
  bool inside = false;
  for (const std::string& line : run_cli("--help").lines()) {
    if (inside && line.rfind("  ", 0) == 0 && line[2] != ' ') {
      names.push_back(line.substr(2, line.find(' ', 2) - 2));
    }
    if (!line.empty() && line.back() == ':') inside = line == "Subcommands:";
  }
  return names;
}

/// The default CLI11 shows for `flag` in `command --help`, "" when none. CLI11 writes it at
/// the end of the option's column (its name, type and checks; the description follows after
/// two spaces or on the next line): "--flag TYPE=DEFAULT" up to 2.3 (Debian 12 has 2.1),
/// "--flag TYPE [DEFAULT]" from 2.4 (Debian 13), where the checks may hold brackets too
/// ("INT:NUMBER in [1, 1e+09] [1000]"). The column alone is read: a description's
/// "key=value" is no default.
std::string help_default(const std::string& command, const std::string& flag) {
  const std::string text = help_text(command, flag);
  std::string column = text.substr(0, text.find('\n'));
  column.erase(0, column.find(flag));
  column = column.substr(0, column.find("  "));
  std::smatch match;
  static const std::regex shown_default(R"((?:=(\S+)|\[([^\],]+)\])\s*$)");
  if (!std::regex_search(column, match, shown_default)) return "";
  return match[1].matched ? match[1].str() : match[2].str();
}

TEST(CliConsistency, ParserRefusalsAreOneLineWithStatusOne) {
  expect_one_line_error(run_cli("train --config configs/pendulm.yaml"), "upkie-rl",
                        "--config: File does not exist: configs/pendulm.yaml");
  expect_one_line_error(run_cli("rollout --env Upkie-Bullet-Pendulum --no-such-flag"), "upkie-rl",
                        "--no-such-flag");
  expect_one_line_error(run_cli("rollout"), "upkie-rl", "--env is required");
  expect_one_line_error(run_cli("rollout --env Upkie-Bullet-Pendulum --episodes 0"), "upkie-rl",
                        "--episodes");
  expect_one_line_error(run_agent_cli("--model " + kPendulum + " --no-such-flag"), "upkie-rl-agent",
                        "--no-such-flag");
  expect_one_line_error(run_agent_cli("--model " + kPendulum + " --max-pitch nan"),
                        "upkie-rl-agent", "--max-pitch");
  // Help is no error.
  for (const char* help : {"--help", "rollout --help", "drive --help"}) {
    EXPECT_EQ(run_cli(help).exit_code, 0) << help;
  }
  EXPECT_EQ(run_agent_cli("--help").exit_code, 0);
}

TEST(CliConsistency, AMistypedCommandGetsTheNearestSuggested) {
  expect_one_line_error(run_cli("trian --config " + kPendulumConfig), "upkie-rl",
                        "unknown command \"trian\" (did you mean \"train\"?); commands: envs");
  expect_one_line_error(run_cli("rolout --help"), "upkie-rl", "did you mean \"rollout\"?");
  const CliResult far = run_cli("xyzzy");
  expect_one_line_error(far, "upkie-rl", "unknown command \"xyzzy\"; commands: envs, rollout");
  EXPECT_EQ(far.output.find("did you mean"), std::string::npos) << far.output;
  expect_one_line_error(run_cli(""), "upkie-rl", "a command is required: envs, rollout");
}

TEST(CliConsistency, AMistypedFlagGetsTheNearestSuggested) {
  expect_one_line_error(run_cli("rollout --env Upkie-Bullet-Pendulum --episode 2"), "upkie-rl",
                        "--episode (did you mean \"--episodes\"?)");
  // The runner's --model is required: CLI11 says so first, then the flag meant is named.
  expect_one_line_error(run_agent_cli("--modle x.ckpt"), "upkie-rl-agent",
                        "--model is required; unknown flag --modle (did you mean \"--model\"?)");
  // Not a former spelling: `drive --port` is listed as --view-port.
  const CliResult drive = run_cli("drive --env Upkie-MuJoCo-Velocity --prt 0");
  EXPECT_EQ(drive.output.find("did you mean \"--port\""), std::string::npos) << drive.output;
}

TEST(CliConsistency, AMistypedEnvironmentIdGetsTheNearestSuggested) {
  const std::string suggestion = "(did you mean \"Upkie-MuJoCo-Pendulum\"?); registered ids: ";
  expect_one_line_error(run_cli("rollout --env Upkie-Mujoco-Pendulum"), "upkie-rl",
                        "--env: environment id \"Upkie-Mujoco-Pendulum\" not found " + suggestion);
  expect_one_line_error(run_cli("evaluate --env Upkie-MuJoCo-Pendulm --controller zero"),
                        "upkie-rl", suggestion);
  expect_one_line_error(run_cli("bench --env Upkie-MuJoCo-Pendlum"), "upkie-rl", suggestion);
  expect_one_line_error(run_cli("drive --env Upkie-MuJoCo-Velocty"), "upkie-rl",
                        "(did you mean \"Upkie-MuJoCo-Velocity\"?)");
  // Checked before the log is even looked for.
  expect_one_line_error(run_cli("identify --log absent.mpack --env Upkie-Mujoco-Servos"),
                        "upkie-rl", "(did you mean \"Upkie-MuJoCo-Servos\"?)");
}

TEST(CliConsistency, AMistypedConfigKeyGetsTheNearestSuggested) {
  const auto run_dir = testing::temp_path("cli_consistency_run");
  expect_one_line_error(run_cli("train --config " + kPendulumConfig + " --run-dir " +
                                run_dir.string() + " --set ppo.total_timestep=1000"),
                        "upkie-rl",
                        "unknown config key 'ppo.total_timestep' (did you mean "
                        "\"ppo.total_timesteps\"?)");
  EXPECT_FALSE(std::filesystem::exists(run_dir));
}

TEST(CliConsistency, AMistypedEnvironmentOptionGetsTheNearestSuggested) {
  const CliResult result =
      run_cli("rollout --env Upkie-Bullet-Pendulum --env-option observaton_noise=0.1");
  expect_one_line_error(result, "upkie-rl",
                        "unknown option \"observaton_noise\" (did you mean "
                        "\"observation_noise\"?); valid options: frequency");
}

TEST(CliConsistency, DriveTakesTheViewerFlagsOfEveryCommand) {
  for (const char* flag : {"--view-host", "--view-port", "--view-wait", "--view-speed"}) {
    EXPECT_NE(help_text("drive", flag), "") << flag;
    EXPECT_NE(help_text("rollout", flag), "") << flag;
  }
  for (const char* former : {"--host", "--port", "--wait", "--speed"}) {
    EXPECT_EQ(help_text("drive", former), "") << former;
  }
  const CliResult drive = run_cli(
      "drive --env Upkie-MuJoCo-Velocity --view-port 0 --view-speed 10 --duration 0.1", 120);
  EXPECT_EQ(drive.exit_code, 0) << drive.output;
  // The former spellings still work, with a one-line note each.
  const CliResult former =
      run_cli("drive --env Upkie-MuJoCo-Velocity --port 0 --speed 10 --duration 0.1", 120);
  EXPECT_EQ(former.exit_code, 0) << former.output;
  EXPECT_NE(former.output.find("upkie-rl: note: drive --port is now --view-port"),
            std::string::npos)
      << former.output;
  EXPECT_NE(former.output.find("upkie-rl: note: drive --speed is now --view-speed"),
            std::string::npos)
      << former.output;
  // And are checked as the current ones are.
  expect_one_line_error(run_cli("drive --env Upkie-MuJoCo-Velocity --speed 100"), "upkie-rl",
                        "error: --speed: 100 is not a finite number in [0.05, 10]");
}

TEST(CliConsistency, ThreadsZeroMeansTheCallingThreadInEveryCommand) {
  const std::string bench = help_text("bench", "--threads");
  const std::string evaluate = help_text("evaluate", "--threads");
  for (const std::string& help : {bench, evaluate}) {
    EXPECT_NE(help.find("0: the calling thread alone, no thread pool"), std::string::npos) << help;
  }
  EXPECT_NE(evaluate.find("default: one per core"), std::string::npos) << evaluate;
  // Evaluate's figures with 0 are those of any other count: EvaluateCommand's
  // ResultsDoNotDependOnTheThreadCount.
}

TEST(CliConsistency, MaxStepsHasOneDefault) {
  EXPECT_EQ(help_default("rollout", "--max-steps"), "1000");
  EXPECT_EQ(help_default("evaluate", "--max-steps"), "1000");
}

/// A command that declared --episodes, --seed or --env-option by itself, with another bound or
/// check, fails here: every subcommand's help must show common_flags.hpp's.
TEST(CliConsistency, SharedFlagsHaveOneCheckAndOneWordingInEveryCommand) {
  // The commands that take each flag, to be sure the loop below looks at them.
  const std::vector<std::string> with_episodes = {"rollout", "evaluate"};
  const std::vector<std::string> with_seed = {"rollout", "drive", "evaluate", "train", "identify"};
  const std::vector<std::string> with_env_option = {"rollout", "drive", "evaluate", "bench",
                                                    "identify"};
  // Each flag's type and check ([1, 1e6]: the episodes bound of docs/python.md), then the
  // start or end of its help, as common_flags.hpp declares them.
  const std::vector<std::array<std::string, 3>> shared = {
      {"--episodes", "--episodes INT:NUMBER in [1, 1e+06]", "Number of episodes"},
      {"--seed", "--seed UINT:SEED in [0, 2^64 - 1]", "Seed of "},
      {"--env-option", "--env-option TEXT ...",
       "(repeatable; `upkie-rl envs --options` lists them)"}};
  std::map<std::string, std::vector<std::string>> takers;
  const std::vector<std::string> commands = subcommands();
  ASSERT_GE(commands.size(), 14u);
  for (const std::string& command : commands) {
    const CliResult help = run_cli(command + " --help");
    ASSERT_EQ(help.exit_code, 0) << command << "\n" << help.output;
    for (const auto& [flag, check, wording] : shared) {
      const std::string text = flag_help(help, flag);
      if (text.empty()) continue;
      takers[flag].push_back(command);
      EXPECT_NE(text.find(check), std::string::npos) << command << "\n" << text;
      EXPECT_NE(text.find(wording), std::string::npos) << command << "\n" << text;
    }
  }
  for (const auto& [flag, expected] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {"--episodes", with_episodes},
           {"--seed", with_seed},
           {"--env-option", with_env_option}}) {
    for (const std::string& command : expected) {
      EXPECT_NE(std::find(takers[flag].begin(), takers[flag].end(), command), takers[flag].end())
          << command << " " << flag;
    }
  }
}

/// Apart from the check above: CLI11 2.4 shows defaults otherwise (as for
/// MaxStepsHasOneDefault, docs/install.md).
TEST(CliConsistency, SharedFlagsKeepEachCommandsDefault) {
  EXPECT_EQ(help_default("rollout", "--episodes"), "1");
  EXPECT_EQ(help_default("evaluate", "--episodes"), "10");
  for (const char* command : {"rollout", "drive", "evaluate", "identify"}) {
    EXPECT_EQ(help_default(command, "--seed"), "0") << command;
  }
  // Train's seed is the configuration's unless given: no default shown.
  EXPECT_EQ(help_default("train", "--seed"), "");
}

TEST(CliConsistency, BothToolsPrintTheirVersion) {
  const std::regex version(R"(^[0-9]+\.[0-9]+\.[0-9]+ \(commit [0-9a-f]{40}(-dirty)?\)\n$)");
  const CliResult cli = run_cli("--version");
  EXPECT_EQ(cli.exit_code, 0) << cli.output;
  EXPECT_EQ(cli.output.rfind("upkie-rl ", 0), 0u) << cli.output;
  const CliResult agent = run_agent_cli("--version");
  EXPECT_EQ(agent.exit_code, 0) << agent.output;
  ASSERT_EQ(agent.output.rfind("upkie-rl-agent ", 0), 0u) << agent.output;
  // The same version and commit: the two tools of one build.
  EXPECT_EQ(agent.output.substr(std::string("upkie-rl-agent ").size()),
            cli.output.substr(std::string("upkie-rl ").size()));
}

TEST(CliConsistency, EveryModelFormatInfoReadsRunsOrIsRefusedWithWhatToRun) {
  const auto directory = testing::temp_path("cli_consistency_models");
  std::filesystem::create_directories(directory);
  const std::string onnx = (directory / "policy.onnx").string();
  ASSERT_EQ(run_cli("export " + kPendulum + " --onnx " + onnx).exit_code, 0);
  ASSERT_EQ(run_cli("info " + onnx).exit_code, 0);
  const std::string rollout = "rollout --env Upkie-Bullet-Pendulum --max-steps 5 --model ";
  const CliResult from_onnx = run_cli(rollout + onnx);
  expect_one_line_error(from_onnx, "upkie-rl", "model " + onnx + " is an ONNX export");
  EXPECT_NE(from_onnx.output.find("give the checkpoint (.ckpt) it was made from"),
            std::string::npos)
      << from_onnx.output;
  EXPECT_EQ(from_onnx.output.find("bad magic"), std::string::npos) << from_onnx.output;
  // A TorchScript file beside its checkpoint, as `train` writes them: that checkpoint.
  const auto torchscript = directory / "model_1.pt";
  testing::write_bytes(torchscript, "PK\x03\x04 not read");
  std::filesystem::copy_file(kPendulum, directory / "model_1.ckpt");
  expect_one_line_error(
      run_cli(rollout + torchscript.string()), "upkie-rl",
      "give " + (directory / "model_1.ckpt").string() + ", the checkpoint beside it");
  ASSERT_EQ(run_cli(rollout + (directory / "model_1.ckpt").string()).exit_code, 0);
  const auto zip = directory / "ppo.zip";
  testing::write_bytes(zip, "PK\x03\x04 not read");
  expect_one_line_error(run_cli(rollout + zip.string()), "upkie-rl", "upkie_rl.sb3_convert import");
  // Every runner refuses alike: evaluate, and the robot runner, which stops before it
  // touches the spine as for any file it cannot run (status 2, the reason in its summary).
  expect_one_line_error(
      run_cli("evaluate --env Upkie-Bullet-Pendulum --episodes 1 --max-steps 5 --model " + onnx),
      "upkie-rl", "is an ONNX export");
  const CliResult agent =
      run_agent_cli("--model " + onnx + " --shm-name /upkie_rl_cli_consistency --open-tries 1");
  EXPECT_EQ(agent.exit_code, 2) << agent.output;
  EXPECT_NE(agent.output.find("is an ONNX export"), std::string::npos) << agent.output;
  std::filesystem::remove_all(directory);
}

TEST(CliConsistency, TheAgentHelpNamesCommandsThatExist) {
  const CliResult help = run_agent_cli("--help");
  ASSERT_EQ(help.exit_code, 0) << help.output;
  EXPECT_EQ(help.output.find("--replay"), std::string::npos) << help.output;
  EXPECT_NE(help.output.find("`upkie-rl view FILE` replays it"), std::string::npos) << help.output;
  // `view FILE` is how `view` takes a record.
  const CliResult view = run_cli("view --help");
  EXPECT_NE(view.output.find("record TEXT:FILE"), std::string::npos) << view.output;
  EXPECT_NE(run_cli("view --replay x.csv").exit_code, 0);
}

}  // namespace
}  // namespace upkie_rl
