#pragma once
/// @file
/// identify(): the environment options that make a simulation predict a robot's log best.

#include <cstdint>
#include <string>
#include <vector>

#include "envs/core/env_options.hpp"
#include "envs/records/robot_log.hpp"
#include "identify/identified_parameter.hpp"
#include "identify/log_replay.hpp"

namespace upkie_rl {

/// What to fit, on what, and how hard.
struct IdentificationSettings {
  std::string env_id = "Upkie-Bullet-Servos";
  EnvOptions options;  ///< Fixed options of the environment.
  std::vector<ParameterRequest> parameters;
  ReplaySettings replay;
  int max_evaluations = 120;  ///< Of the search's continuous fit (on half the replays; run_fit).
  std::uint64_t seed = 0;     ///< NLopt's (BOBYQA itself draws nothing).
};

/// One fitted parameter.
struct FittedParameter {
  std::string name;
  std::string unit;
  double value = 0.0;
  /// One standard deviation [unit of the value]: the spread of the fit over replays, from
  /// the errors' Jacobian with each replay an independent block (cluster-robust sandwich
  /// covariance). For a delay fitted with a lag, 1 step when a neighbouring delay, with the
  /// other parameters refitted, predicts the log not worse beyond chance (paired_replay_z
  /// under 2), else 0; 0 for a delay fitted without a lag. It does not include the bias of
  /// a model that cannot match the robot (another engine, the no-slip start states).
  double uncertainty = 0.0;
  bool identifiable = true;
  std::string reason;  ///< Why not, when not identifiable.
  /// The values the log cannot tell from the fit: with the other parameters at the fit, on
  /// each side the nearest value that predicts the log worse beyond chance (paired_replay_z
  /// of 2 or more against the fit, replay by replay, on a quarter of the replays), found in
  /// steps out from the fit and erring wide; the bound itself when none does, as when the
  /// log bounds a parameter on one side only. Unlike
  /// `uncertainty` it holds where the prediction error is flat or kinked (the floor's
  /// friction, shown only where a tire slips). Conditional on the others: a delay one step
  /// off (uncertainty 1) moves the lag's. The value itself for a delay, the measured
  /// gyroscope bias and a parameter not identifiable.
  double low = 0.0;
  double high = 0.0;
};

struct IdentificationResult {
  std::vector<FittedParameter> parameters;
  double rmse_before = 0.0;      ///< With the nominal values (normalised errors, no unit).
  double rmse_after = 0.0;       ///< With the fitted ones.
  double seconds = 0.0;          ///< Wall time of the fit [s].
  int evaluations = 0;           ///< Replays of the whole log.
  std::size_t windows = 0;       ///< Replays per evaluation.
  std::size_t windows_down = 0;  ///< Replays left out: the robot was down in them.
  /// Replays started later, off tire slip (ReplaySettings::slip_threshold).
  std::size_t windows_moved_off_slip = 0;
  double horizon = 0.0;   ///< Of each replay [s].
  double timestep = 0.0;  ///< The environment's step [s], a delay's unit.
};

/// Fits the requested parameters: the delay (whole steps) by scanning its range, the others
/// with NLopt's BOBYQA (bounded, derivative-free) within their ranges, starting from the
/// nominal robot; then the delay again at the fitted values. Same log and settings, same
/// result.
/// @throws RobotLogError when the log cannot be replayed (see LogReplay).
/// @throws std::invalid_argument on a bad environment, option or parameter.
IdentificationResult identify(const RobotLog& log, const IdentificationSettings& settings);

/// `{"params": {name: value}, "rmse_before": x, "rmse_after": y, "seconds": s}` plus each
/// parameter's uncertainty, interval (`[low, high]`) and identifiability, on one line.
std::string identification_json(const IdentificationResult& result);

/// When the delay is uncertain by a step and a lag was fitted with it, what the log does pin
/// down, on one line: a delay and a lag shift the commands alike, so their sum, delay x
/// step + lag, is what to trust. "" otherwise.
std::string actuation_latency_line(const IdentificationResult& result);

/// The fitted options as a YAML training-configuration fragment (env.options), with the
/// matching `--env-option` and `--set` arguments in its comments; the parameters not
/// identifiable from the log are left out, each named with its reason in a comment.
std::string identification_yaml(const IdentificationResult& result, const std::string& log_name,
                                const std::string& env_id);

}  // namespace upkie_rl
