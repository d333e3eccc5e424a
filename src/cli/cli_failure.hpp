#pragma once
/// @file
/// The failure grammar of both command-line tools, `upkie-rl` and `upkie-rl-agent`: --help
/// and --version print and exit 0; every refusal, CLI11's own included, ends as one line
/// "<tool>: error: <what>" on the standard error with exit status 1. Header-only: the robot
/// runner is built from its own few sources (cmake/agent_only.cmake).

#include <CLI/CLI.hpp>
#include <exception>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "base/closest_name.hpp"
#include "policy/build_info.hpp"

namespace upkie_rl::apps {

/// The group of the former spellings of flags (add_former_spelling): accepted, never listed
/// in --help nor suggested. (CLI11's own hidden group, "", would leave their names out of
/// its refusals.)
inline constexpr const char* kFormerSpellings = "Former spellings";

/// Adds --version: "<tool> <version> (commit <git commit>)".
inline void add_version_flag(CLI::App& app, const std::string& tool) {
  app.set_version_flag("--version",
                       tool + " " + upkie_rl_version() + " (commit " + upkie_rl_git_commit() + ")");
}

/// The first argument of the command `app` parsed last that is an unknown flag ("--name",
/// without "=value"), or "".
inline std::string unknown_flag(const CLI::App& command) {
  for (const std::string& argument : command.remaining()) {
    if (argument.rfind("--", 0) == 0) return argument.substr(0, argument.find('='));
  }
  return "";
}

/// The refusal of a parse: CLI11's message, then, when an unknown flag is behind it, the
/// nearest listed one. (CLI11 reports a missing required option before an unknown flag,
/// which may be that option mistyped: the unknown flag is then named too.)
inline std::string parse_refusal(const CLI::App& app, const CLI::ParseError& error) {
  const CLI::App* command = &app;
  while (!command->get_subcommands().empty()) command = command->get_subcommands().back();
  const bool extras = dynamic_cast<const CLI::ExtrasError*>(&error) != nullptr;
  const bool required = dynamic_cast<const CLI::RequiredError*>(&error) != nullptr;
  const std::string flag = unknown_flag(*command);
  if (flag.empty() || !(extras || required)) return error.what();
  std::vector<std::string> flags;
  for (const CLI::Option* option : command->get_options()) {
    if (!option->get_positional() && option->get_group() != kFormerSpellings) {
      flags.push_back(option->get_name());
    }
  }
  return std::string(error.what()) + (extras ? "" : "; unknown flag " + flag) +
         did_you_mean(flag, flags);
}

/// The status of a parse CLI11 ended: --help and --version print what they show and give 0;
/// a refusal prints "<tool>: error: " and parse_refusal, and gives 1 (CLI11's own codes, 105
/// and the like, would tell scripts nothing more).
inline int parse_exit_status(const CLI::App& app, const CLI::ParseError& error,
                             const std::string& tool) {
  if (error.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(error);
  std::cerr << tool << ": error: " << parse_refusal(app, error) << std::endl;
  return 1;
}

/// Runs `run` and turns any exception it lets through into one line "<tool>: error: <what>"
/// and status 1; otherwise returns run's status.
inline int run_reporting_errors(const std::string& tool, const std::function<int()>& run) {
  try {
    return run();
  } catch (const std::exception& error) {
    std::cerr << tool << ": error: " << error.what() << std::endl;
  } catch (...) {
    std::cerr << tool << ": error: unknown exception" << std::endl;
  }
  return 1;
}

}  // namespace upkie_rl::apps
