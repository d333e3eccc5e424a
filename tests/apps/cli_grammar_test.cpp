/// One grammar for every `upkie-rl` command: --version, the same option names for the same
/// things, required options marked in --help, and every listed choice accepted.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "apps/cli_runner.hpp"
#include "common/temp_files.hpp"

namespace upkie_rl {
namespace {

using testing::run_cli;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(CliGrammar, VersionIsPrinted) {
  const auto result = run_cli("--version");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(result.output.rfind("upkie-rl 0.1.0 (commit ", 0), 0u) << result.output;
}

TEST(CliGrammar, RequiredOptionsAreMarkedInHelp) {
  const auto render = run_cli("render --help");
  ASSERT_EQ(render.exit_code, 0) << render.output;
  for (const std::string& line : render.lines()) {
    if (contains(line, "--video ")) EXPECT_TRUE(contains(line, "REQUIRED")) << line;
  }
  const auto missing = run_cli("render /dev/null");
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_TRUE(contains(missing.output, "--video is required")) << missing.output;
}

TEST(CliGrammar, TheViewerAddressHasOneNameInEveryCommand) {
  for (const char* command : {"view", "rollout", "train"}) {
    const auto help = run_cli(std::string(command) + " --help");
    EXPECT_TRUE(contains(help.output, "--view-host")) << command;
    EXPECT_TRUE(contains(help.output, "--view-port")) << command;
    EXPECT_FALSE(contains(help.output, "--host")) << command;
  }
  // The former spelling of `view` still works, unlisted.
  const auto page = testing::temp_path("grammar.html");
  const auto html = run_cli("view --host 127.0.0.1 --port 0 --html " + page.string());
  EXPECT_EQ(html.exit_code, 0) << html.output;
  std::filesystem::remove(page);
  const auto sweep = run_cli("sweep --help");
  EXPECT_TRUE(contains(sweep.output, "--output")) << sweep.output;
  EXPECT_FALSE(contains(sweep.output, "--out ")) << sweep.output;
}

TEST(CliGrammar, EveryListedControllerIsAcceptedByEveryCommand) {
  for (const char* controller : {"zero", "linear:10,1,0,0.1", "lqr", "lqr:0.1,1,1,1,1"}) {
    const std::string spec = controller;
    const auto bench = run_cli("bench --env Upkie-Bullet-Pendulum --steps 10 --controller " + spec);
    EXPECT_EQ(bench.exit_code, 0) << spec << ": " << bench.output;
    const auto rollout =
        run_cli("rollout --env Upkie-Bullet-Pendulum --max-steps 10 --controller " + spec);
    EXPECT_EQ(rollout.exit_code, 0) << spec << ": " << rollout.output;
    const auto evaluate = run_cli(
        "evaluate --env Upkie-Bullet-Pendulum --episodes 1 --max-steps 10 --controller " + spec);
    EXPECT_EQ(evaluate.exit_code, 0) << spec << ": " << evaluate.output;
  }
  for (const char* command : {"bench", "rollout", "evaluate"}) {
    const auto help = run_cli(std::string(command) + " --help");
    EXPECT_TRUE(contains(help.output, "lqr (designed on this environment")) << command;
  }
}

}  // namespace
}  // namespace upkie_rl
