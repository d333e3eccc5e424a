/// @file
/// `upkie-rl identify`: the environment options that make a simulation predict a robot's log.

#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/commands.hpp"
#include "base/atomic_file.hpp"
#include "base/number_text.hpp"
#include "cli/common_flags.hpp"
#include "cli/option_checks.hpp"
#include "envs/core/env_options.hpp"
#include "envs/records/robot_log.hpp"
#include "identify/identification.hpp"
#include "identify/measured_reset_state.hpp"

namespace upkie_rl::apps {
namespace {

struct IdentifyOptions {
  std::string log_path;
  std::string env_id = "Upkie-Bullet-Servos";
  std::vector<std::string> params;
  std::vector<std::string> env_options;
  std::string output_path;
  bool json = false;
  ReplaySettings replay;
  int max_evaluations = IdentificationSettings{}.max_evaluations;
  std::uint64_t seed = 0;
};

/// "; predicts alike from LOW to HIGH UNIT" when the values the log cannot tell from the
/// fit reach wider than its uncertainty says, or "".
std::string interval_text(const FittedParameter& parameter, const std::string& unit) {
  if (parameter.high - parameter.low <= 4.0 * parameter.uncertainty) return "";
  char text[96];
  std::snprintf(text, sizeof(text), "; predicts alike from %.4g to %.4g%s", parameter.low,
                parameter.high, unit.c_str());
  return text;
}

void print_result(const IdentificationResult& result, const RobotLog& log) {
  std::printf("%s: %zu cycles, %.2f s at %.0f Hz; %zu replays of %.3g s, %d evaluations\n",
              log.name.c_str(), log.cycles.size(), log.duration(), 1.0 / log.period(),
              result.windows, result.horizon, result.evaluations);
  if (result.windows_moved_off_slip > 0) {
    std::printf("  %zu replays start later, off tire slip (the accelerometer against the wheels)\n",
                result.windows_moved_off_slip);
  }
  if (result.windows_down > 0) {
    std::printf("  %zu replays left out: the robot was down (tilted beyond %g rad) in them\n",
                result.windows_down, kFallenTilt);
  }
  for (const FittedParameter& parameter : result.parameters) {
    const std::string unit = parameter.unit.empty() ? "" : " " + parameter.unit;
    if (parameter.identifiable) {
      std::printf("  %-20s %-12s +- %.3g%s%s\n", parameter.name.c_str(),
                  shortest_text(parameter.value).c_str(), parameter.uncertainty, unit.c_str(),
                  interval_text(parameter, unit).c_str());
    } else {
      std::printf("  %-20s %-12s not identifiable from this log: %s\n", parameter.name.c_str(),
                  shortest_text(parameter.value).c_str(), parameter.reason.c_str());
    }
  }
  const std::string latency = actuation_latency_line(result);
  if (!latency.empty()) std::printf("  %s\n", latency.c_str());
  std::printf("rmse_before %.4g, rmse_after %.4g (normalised errors over %.3g s), %.1f s\n",
              result.rmse_before, result.rmse_after, result.horizon, result.seconds);
}

void run_identify(const IdentifyOptions& options) {
  IdentificationSettings settings;
  settings.env_id = options.env_id;
  settings.options = parse_env_options(options.env_options);
  settings.parameters = parse_parameter_requests(options.params);
  settings.replay = options.replay;
  settings.max_evaluations = options.max_evaluations;
  settings.seed = options.seed;
  const RobotLog log = read_robot_log(options.log_path);
  const IdentificationResult result = identify(log, settings);
  print_result(result, log);
  if (!options.output_path.empty()) {
    write_file_atomically<std::runtime_error>(
        options.output_path, identification_yaml(result, options.log_path, options.env_id));
    std::printf("options written to %s\n", options.output_path.c_str());
  }
  if (options.json) std::printf("%s\n", identification_json(result).c_str());
  std::fflush(stdout);
}

}  // namespace

void add_identify_command(CLI::App& app) {
  auto options = std::make_shared<IdentifyOptions>();
  CLI::App* command = app.add_subcommand(
      "identify",
      "Fit environment options (masses, payload, floor friction, actuation delay and lag, torque "
      "limit) to a robot's log by short replays from its measured states");
  command
      ->add_option("--log", options->log_path,
                   "Spine log (mpacklog, Upkie's spines or `upkie-rl spine --log`) or record "
                   "file with servo commands")
      ->required()
      ->check(kNonEmptyPath);
  add_env_id_option(*command, options->env_id, "Environment whose servos replay the log")
      ->capture_default_str();
  command->add_option("--param", options->params,
                      "NAME or NAME=LOW:HIGH to fit (repeatable; default mass_scale, "
                      "floor_friction, action_delay, action_lag)");
  add_env_option_option(*command, options->env_options, ", held fixed in the fit");
  command
      ->add_option("--output", options->output_path,
                   "Write the fitted options as YAML (env.options of a training config)")
      ->check(kNonEmptyPath);
  add_json_flag(*command, options->json);
  command->add_option("--horizon", options->replay.horizon, "Each replay's duration [s]")
      ->capture_default_str()
      ->check(finite_range(0.01, 5.0));
  command->add_option("--window-spacing", options->replay.window_spacing, "Between replays [s]")
      ->capture_default_str()
      ->check(finite_range(0.005, 60.0));
  command
      ->add_option("--max-windows", options->replay.max_windows,
                   "At most this many replays, spread evenly over the log")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  command
      ->add_option("--slip-threshold", options->replay.slip_threshold,
                   "Replays start where the accelerometer and the wheels agree within it, off "
                   "tire slip [m/s]; 0: at fixed starts (logs without an accelerometer too)")
      ->capture_default_str()
      ->check(finite_range(0.0, 10.0));
  command
      ->add_option("--max-evaluations", options->max_evaluations,
                   "Evaluations of the search's continuous fit (each on half the replays)")
      ->capture_default_str()
      ->check(CLI::Range(10, 100000));
  add_seed_option(*command, options->seed, "the fit");
  command->callback([options] { run_identify(*options); });
}

}  // namespace upkie_rl::apps
