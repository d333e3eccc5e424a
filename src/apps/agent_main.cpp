/// @file
/// Entry point of `upkie-rl-agent`, the robot runner: a trained policy on a spine (the
/// robot's, or `upkie-rl spine`) under the safety supervisor, without Python, libtorch or a
/// physics engine.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>
#include <string>

#include "agent/policy_runner.hpp"
#include "base/option_table.hpp"
#include "cli/cli_failure.hpp"
#include "cli/interrupt_handlers.hpp"
#include "cli/option_checks.hpp"
#include "spine/shared_memory.hpp"
#include "spine/spine_error.hpp"

namespace {

using upkie_rl::SupervisorLimits;
using upkie_rl::apps::finite_range;
using upkie_rl::apps::kNonEmptyPath;

/// One flag per supervisor limit, from the limits' own declarations: --max-pitch for
/// max_pitch, checked against the declared range when parsed; `table` must outlive parsing.
void add_limit_options(CLI::App& app, SupervisorLimits& limits, upkie_rl::OptionTable& table) {
  limits.declare_options(table);
  for (const upkie_rl::OptionInfo& info : table.info()) {
    std::string flag = "--" + info.name;
    std::replace(flag.begin(), flag.end(), '_', '-');
    app.add_option_function<std::string>(
           flag,
           [&table, name = info.name, flag](const std::string& text) {
             table.read(name, text, flag);
           },
           info.help)
        ->type_name(info.type == upkie_rl::OptionInfo::Type::kInteger ? "INT" : "FLOAT")
        ->default_str(info.default_value)
        ->check(finite_range(info.min, info.max));
  }
}

/// A shared-memory name the spine layer accepts ('/' and up to 250 other characters).
const CLI::Validator kShmName(
    [](std::string& name) {
      try {
        upkie_rl::SharedMemory::validate_name(name);
        return std::string();
      } catch (const upkie_rl::SpineError& error) {
        return std::string(error.what());
      }
    },
    "NAME");

constexpr const char* kTool = "upkie-rl-agent";

int run(int argc, char** argv) {
  CLI::App app{
      "upkie-rl-agent: runs a policy of `upkie-rl train` on Upkie's spine (the robot's, or "
      "`upkie-rl spine`) under a safety supervisor. Ctrl-C or SIGTERM stops it cleanly."};
  upkie_rl::apps::add_version_flag(app, kTool);
  upkie_rl::RunnerOptions options;
  app.add_option("--model", options.model, "Checkpoint (.ckpt) of `upkie-rl train`")
      ->required()
      ->check(kNonEmptyPath);
  app.add_option("--shm-name", options.shm_name, "Shared-memory name of the spine")
      ->capture_default_str()
      ->check(kShmName);
  // A week at most: longer runs are runs until stopped (0).
  app.add_option("--duration", options.duration, "Run for this long [s], 0 until stopped")
      ->capture_default_str()
      ->check(finite_range(0.0, 7 * 86400.0));
  app.add_option("--record", options.record,
                 "Flight record: every cycle to a CSV file in the format of `upkie-rl rollout "
                 "--record` (`upkie-rl view FILE` replays it)")
      ->check(kNonEmptyPath);
  app.add_flag("--dry-run", options.dry_run,
               "Send only stop commands; log the commands the policy would send");
  app.add_option("--open-tries", options.open_tries, "Attempts at opening the spine, 1 s apart")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  CLI::Option* commands =
      app.add_option("--commands", options.commands,
                     "Velocity tasks: commands from a CSV file of rows time,vx,wz ([s], [m/s], "
                     "[rad/s], each held until the next row's time, as `upkie-rl rollout "
                     "--commands`), or - for lines vx,wz on the standard input, each taking "
                     "effect when read; without it, or --keyboard, the robot stands still")
          ->check(kNonEmptyPath);
  app.add_flag("--keyboard", options.keyboard,
               "Velocity tasks: steer with the keys of the terminal (w/s forward, a/d turn, "
               "space stop)")
      ->excludes(commands);
  upkie_rl::OptionTable limit_options;
  add_limit_options(app, options.limits, limit_options);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // A refused option ends before the spine is touched.
    return upkie_rl::apps::parse_exit_status(app, error, kTool);
  }
  const upkie_rl::apps::InterruptHandlers handlers;
  const upkie_rl::RunSummary summary =
      upkie_rl::run_policy(options, upkie_rl::apps::interrupt_requested);
  std::cout << summary.to_string() << std::endl;
  if (summary.stop_cut_short) {
    std::cerr << "upkie-rl-agent: stopping cut short by a second interrupt after "
              << summary.stop_cycles_sent << " of " << options.limits.nb_stop_cycles
              << " stop cycles; the Stop request was sent" << std::endl;
    return 3;
  }
  return summary.completed ? 0 : 2;
}

}  // namespace

int main(int argc, char** argv) {
  // Every failure ends as one line and status 1; a run the supervisor stopped, status 2; a
  // stop cut short by a second interrupt, status 3.
  return upkie_rl::apps::run_reporting_errors(kTool, [&] { return run(argc, argv); });
}
