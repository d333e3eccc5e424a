/// @file
/// Entry point of `upkie-rl-agent`, the robot runner: a trained policy on a spine (the
/// robot's, or `upkie-rl spine`) under the safety supervisor, without Python, libtorch or a
/// physics engine.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

#include "agent/policy_runner.hpp"
#include "cli/cli_failure.hpp"
#include "cli/interrupt_handlers.hpp"
#include "cli/option_checks.hpp"
#include "spine/shared_memory.hpp"
#include "spine/spine_error.hpp"

namespace {

using upkie_rl::LimitRange;
using upkie_rl::SupervisorLimits;
using upkie_rl::apps::finite_range;
using upkie_rl::apps::kNonEmptyPath;

/// A number option checked against its declared range (finite, within it).
template <typename Number>
void add_ranged_option(CLI::App& app, const std::string& flag, Number& value, LimitRange range,
                       const std::string& help) {
  app.add_option(flag, value, help)
      ->capture_default_str()
      ->check(finite_range(range.min, range.max));
}

void add_limit_options(CLI::App& app, SupervisorLimits& limits) {
  add_ranged_option(app, "--max-pitch", limits.max_pitch, SupervisorLimits::kMaxPitchRange,
                    "Attitude limit: |pitch| [rad]");
  add_ranged_option(app, "--max-roll", limits.max_roll, SupervisorLimits::kMaxRollRange,
                    "Attitude limit: |roll| [rad]");
  add_ranged_option(app, "--joint-position-margin", limits.joint_position_margin,
                    SupervisorLimits::kJointPositionMarginRange,
                    "Measured joint angle allowed beyond the joint's limits [rad]");
  add_ranged_option(app, "--joint-velocity-factor", limits.joint_velocity_factor,
                    SupervisorLimits::kJointVelocityFactorRange,
                    "Measured joint velocity allowed, as a fraction of the joint's limit");
  add_ranged_option(app, "--velocity-command-rate", limits.max_velocity_command_rate,
                    SupervisorLimits::kVelocityCommandRateRange,
                    "Rate limit of velocity commands [rad/s^2]");
  add_ranged_option(app, "--position-command-rate", limits.max_position_command_rate,
                    SupervisorLimits::kPositionCommandRateRange,
                    "Rate limit of position commands [rad/s]");
  add_ranged_option(app, "--max-torque", limits.max_torque, SupervisorLimits::kMaxTorqueRange,
                    "Cap of every command's maximum torque [N.m], never above the joint's "
                    "effort (0: the effort)");
  add_ranged_option(app, "--spine-timeout", limits.spine_timeout,
                    SupervisorLimits::kSpineTimeoutRange,
                    "The spine is silent after this long without an answer [s]");
  add_ranged_option(app, "--max-deadline-misses", limits.max_consecutive_deadline_misses,
                    SupervisorLimits::kMaxDeadlineMissesRange,
                    "Stop after this many missed deadlines in a row");
  add_ranged_option(app, "--max-cycle-periods", limits.max_cycle_periods,
                    SupervisorLimits::kMaxCyclePeriodsRange,
                    "Stop after one cycle longer than this many periods");
  add_ranged_option(app, "--stop-cycles", limits.nb_stop_cycles, SupervisorLimits::kStopCyclesRange,
                    "Cycles of stop commands sent before the Stop request (200: 1 s at "
                    "200 Hz); a second Ctrl-C or SIGTERM while stopping cuts them short");
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
  add_limit_options(app, options.limits);
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
