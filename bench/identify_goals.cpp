/// Issue 34's identification goals, measured: logs of a simulated robot with hidden physics
/// (write_excitation_log) for several seeds, fitted by identify() on either engine; prints
/// each fitted parameter against its hidden value, the rmse before and after, and the wall
/// time, then the JSON of each fit. docs/identify.md reports its output.
///
///   identify_goals --log-env Upkie-Bullet-Servos --fit-env Upkie-MuJoCo-Servos \
///     --duration 60 --seeds 1 2 3
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "base/number_text.hpp"
#include "envs/records/robot_log.hpp"
#include "identify/excitation_log.hpp"
#include "identify/identification.hpp"

namespace upkie_rl {
namespace {

struct GoalSettings {
  std::string log_env = "Upkie-Bullet-Servos";
  std::string fit_env = "Upkie-Bullet-Servos";
  double duration = 60.0;
  std::vector<std::uint64_t> seeds = {1, 2, 3};
  /// The hidden physics, as KEY=VALUE environment options of the log's environment.
  std::vector<std::string> hidden = {
      "mass_scale=1.2", "payload_mass=1",      "payload_offset_x=0.04", "floor_friction=0.6",
      "action_delay=2", "action_lag_min=0.03", "action_lag_max=0.03"};
  /// Options the fit is told (an owner weighs the payload but does not know where its mass is).
  std::vector<std::string> known = {"payload_mass=1"};
  std::vector<std::string> params = {"mass_scale=0.6:1.6", "payload_offset_x=-0.1:0.1",
                                     "floor_friction=0.1:1.5", "action_delay=0:4",
                                     "action_lag=0:0.1"};
  ReplaySettings replay;
  int max_evaluations = IdentificationSettings{}.max_evaluations;
  ExcitationSettings excitation;
  bool check_truth = false;
  bool truth_only = false;  ///< The objective at the hidden values, no fit.
};

/// The hidden value of a fitted parameter, NaN when the log's options do not set it.
double hidden_value(const EnvOptions& hidden, const std::string& name) {
  const std::string option = name == "action_lag" ? "action_lag_min" : name;
  for (const auto& [key, value] : hidden) {
    if (key == option) return std::stod(value);
  }
  return std::nan("");
}

void run_seed(const GoalSettings& goals, std::uint64_t seed) {
  const EnvOptions hidden = parse_env_options(goals.hidden);
  const auto path = std::filesystem::temp_directory_path() /
                    ("identify_goals_" + std::to_string(seed) + ".mpack");
  ExcitationSettings excitation = goals.excitation;
  excitation.duration = goals.duration;
  excitation.seed = seed;
  write_excitation_log(goals.log_env, hidden, excitation, path);
  const RobotLog log = read_robot_log(path);
  IdentificationSettings settings;
  settings.env_id = goals.fit_env;
  settings.options = parse_env_options(goals.known);
  settings.parameters = parse_parameter_requests(goals.params);
  settings.replay = goals.replay;
  settings.max_evaluations = goals.max_evaluations;
  // The objective at the hidden values, beside the fit's (or alone).
  if (goals.check_truth || goals.truth_only) {
    int max_delay = 0;
    double max_lag = 0.0;
    ParameterValues truth;
    for (const ParameterRequest& request : settings.parameters) {
      if (request.parameter->name == "action_delay") max_delay = static_cast<int>(request.high);
      if (request.parameter->name == "action_lag") max_lag = request.high;
      truth.emplace_back(request.parameter,
                         hidden_value(hidden, std::string(request.parameter->name)));
    }
    const LogReplay replay(settings.env_id, settings.options, log, settings.replay, max_delay,
                           max_lag);
    std::printf("  rmse at the hidden values %.4f\n", replay.rmse(truth));
    for (std::size_t i = 0; i < truth.size(); ++i) {  // each parameter moved by -20..+20 %
      std::printf("    %s:", std::string(truth[i].first->name).c_str());
      for (const double factor : {0.8, 0.9, 0.95, 1.05, 1.1, 1.2}) {
        if (truth[i].first->integer) continue;
        ParameterValues moved = truth;
        moved[i].second *= factor;
        std::printf(" x%.2f %.4f", factor, replay.rmse(moved));
      }
      std::printf("\n");
    }
  }
  if (goals.truth_only) return;
  const IdentificationResult result = identify(log, settings);
  std::printf("seed %llu: %s -> %s, %.0f s log, %zu replays, %d evaluations, %.1f s wall\n",
              static_cast<unsigned long long>(seed), goals.log_env.c_str(), goals.fit_env.c_str(),
              log.duration(), result.windows, result.evaluations, result.seconds);
  for (const FittedParameter& parameter : result.parameters) {
    const double truth = hidden_value(hidden, parameter.name);
    std::printf(
        "  %-18s hidden %-8s fitted %-10.4g +- %-9.2g error %+7.2f %% in [%.4g, %.4g]%s%s\n",
        parameter.name.c_str(), shortest_text(truth).c_str(), parameter.value,
        parameter.uncertainty, 100.0 * (parameter.value - truth) / truth, parameter.low,
        parameter.high, truth >= parameter.low && truth <= parameter.high ? "" : " MISSES",
        parameter.identifiable ? "" : "  (not identifiable)");
  }
  std::printf("  rmse %.4f -> %.4f (x%.2f)\n  %s\n", result.rmse_before, result.rmse_after,
              result.rmse_before / result.rmse_after, identification_json(result).c_str());
  std::fflush(stdout);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace upkie_rl

int main(int argc, char** argv) {
  upkie_rl::GoalSettings goals;
  CLI::App app{"Measure upkie-rl identify against issue 34's goals"};
  app.add_option("--log-env", goals.log_env, "Environment that writes the logs")
      ->capture_default_str();
  app.add_option("--fit-env", goals.fit_env, "Environment that fits them")->capture_default_str();
  app.add_option("--duration", goals.duration, "Of each log [s]")->capture_default_str();
  app.add_option("--seeds", goals.seeds, "One log per seed")->capture_default_str();
  app.add_option("--hidden", goals.hidden, "The log's physics, KEY=VALUE")->capture_default_str();
  app.add_option("--known", goals.known, "Options the fit is given, KEY=VALUE")
      ->capture_default_str();
  app.add_option("--param", goals.params, "Parameters fitted")->capture_default_str();
  app.add_option("--horizon", goals.replay.horizon, "Each replay's duration [s]")
      ->capture_default_str();
  app.add_option("--window-spacing", goals.replay.window_spacing, "Between replays [s]")
      ->capture_default_str();
  app.add_option("--max-windows", goals.replay.max_windows, "Replays per evaluation at most")
      ->capture_default_str();
  app.add_option("--slip-threshold", goals.replay.slip_threshold,
                 "Replays start off tire slip above it [m/s]; 0: at fixed starts")
      ->capture_default_str();
  app.add_option("--max-evaluations", goals.max_evaluations, "Of the search's continuous fit")
      ->capture_default_str();
  app.add_option("--amplitude", goals.excitation.amplitude, "Largest forward command [m/s]")
      ->capture_default_str();
  app.add_option("--yaw-amplitude", goals.excitation.yaw_amplitude, "Largest yaw rate [rad/s]")
      ->capture_default_str();
  app.add_option("--kick-amplitude", goals.excitation.kick_amplitude,
                 "Largest step added to the ground velocity [m/s]")
      ->capture_default_str();
  app.add_flag("--check-truth", goals.check_truth, "Also print the rmse at the hidden values");
  app.add_flag("--truth-only", goals.truth_only, "Print the rmse at the hidden values, no fit");
  CLI11_PARSE(app, argc, argv);
  try {
    for (const std::uint64_t seed : goals.seeds) upkie_rl::run_seed(goals, seed);
  } catch (const std::exception& error) {  // a bad option, a log whose robot fell: one line
    std::fprintf(stderr, "identify_goals: %s\n", error.what());
    return 1;
  }
  return 0;
}
