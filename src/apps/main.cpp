/// @file
/// Entry point of the `upkie-rl` command-line tool.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/commands.hpp"
#include "base/closest_name.hpp"
#include "cli/cli_failure.hpp"

namespace {

constexpr const char* kTool = "upkie-rl";

std::vector<std::string> command_names(CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
    names.push_back(command->get_name());
  }
  return names;
}

/// Refuses a command line whose first word names no command (CLI11 would only say that a
/// subcommand is required), suggesting the nearest command. The tool's own options are flags,
/// so its first word that is no option is the command.
void check_command_name(CLI::App& app, int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word.rfind('-', 0) == 0) continue;
    const std::vector<std::string> names = command_names(app);
    if (std::find(names.begin(), names.end(), word) != names.end()) return;
    throw std::invalid_argument("unknown command \"" + word + "\"" +
                                upkie_rl::did_you_mean(word, names) +
                                "; commands: " + CLI::detail::join(names, ", "));
  }
}

int run(int argc, char** argv) {
  CLI::App app{
      "upkie-rl: simulate, train, evaluate and deploy balance controllers for Upkie, "
      "the open-source wheeled biped."};
  upkie_rl::apps::add_version_flag(app, kTool);
  app.require_subcommand(1);
  app.fallthrough(false);
  upkie_rl::apps::add_envs_command(app);
  upkie_rl::apps::add_rollout_command(app);
  upkie_rl::apps::add_drive_command(app);
  upkie_rl::apps::add_evaluate_command(app);
  upkie_rl::apps::add_render_command(app);
  upkie_rl::apps::add_view_command(app);
  upkie_rl::apps::add_bench_command(app);
  upkie_rl::apps::add_spine_command(app);
  upkie_rl::apps::add_train_command(app);
  upkie_rl::apps::add_sweep_command(app);
  upkie_rl::apps::add_plot_command(app);
  upkie_rl::apps::add_export_command(app);
  upkie_rl::apps::add_info_command(app);
  upkie_rl::apps::add_identify_command(app);
  check_command_name(app, argc, argv);
  try {
    app.parse(argc, argv);
  } catch (const CLI::RequiredError& error) {
    if (!app.get_subcommands().empty()) return upkie_rl::apps::parse_exit_status(app, error, kTool);
    // No command at all.
    std::cerr << kTool
              << ": error: a command is required: " << CLI::detail::join(command_names(app), ", ")
              << " (`upkie-rl --help` describes them)" << std::endl;
    return 1;
  } catch (const CLI::ParseError& error) {
    return upkie_rl::apps::parse_exit_status(app, error, kTool);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Every failure, setting up the commands included, ends as one line and status 1.
  return upkie_rl::apps::run_reporting_errors(kTool, [&] { return run(argc, argv); });
}
