#pragma once
/// @file
/// LogReplay: how well a simulation with given options predicts a log, by short-horizon
/// replay from the log's measured states.

#include <array>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "envs/core/env_options.hpp"
#include "envs/records/robot_log.hpp"
#include "identify/identified_parameter.hpp"
#include "sim/reset_state.hpp"

namespace upkie_rl {

class ServosEnv;

/// How a log is cut into replays.
struct ReplaySettings {
  double horizon = 0.2;         ///< Each replay's prediction [s].
  double window_spacing = 0.2;  ///< Between replay starts [s].
  /// At most this many replays, spread evenly over the log: the cost of one evaluation
  /// stays bounded on long logs (100 replays of 0.2 s: about a second on one core).
  std::size_t max_windows = 100;
  /// Replays start off tire slip when the log has an accelerometer: each start slides
  /// forward, by less than half the spacing, to the first cycle whose tire_slip_evidence
  /// is at most this [m/s] (to the least evidence when none is); 0 leaves the starts be.
  double slip_threshold = 0.02;
  double slip_span = 0.02;  ///< The span of that evidence [s].
};

/// The measured signals compared, per predicted step: base pitch [rad] and pitch rate
/// [rad/s], the two wheel velocities [rad/s], the four leg joint angles [rad].
inline constexpr std::size_t kNumReplaySignals = 8;

/// Threads replaying a log's windows (the 2 cores of the machines it was written for; a
/// fixed number, so that results do not depend on the machine).
inline constexpr std::size_t kReplayWorkers = 2;

/// A value of each fitted parameter, in the order of the requests.
using ParameterValues = std::vector<std::pair<const IdentifiedParameter*, double>>;

/// The cycle, modulo `stride`, at which the agent's commands take effect in `log` (the most
/// common one where they change), 0 when they never change: where LogReplay samples a log
/// recorded faster than the environment steps.
///
/// Why: a spine logs every 1 ms cycle, an agent writes once per step, at a phase of the
/// step the spine does not choose (the sim2real demo's runner: 5-6 ms into each 20 ms).
/// Sampling at phase 0 paired each observation with the command of the step before, which
/// shifted the fitted actuation by the phase: the demo's 20 ms delay and 10 ms lag fitted as
/// no delay and a 12 ms lag, and as one step and 7.9 ms sampled at the agent's phase.
std::size_t agent_phase(const RobotLog& log, std::size_t stride);

/// Replays a log on one environment id: from each window's first logged cycle (its measured
/// state, measured_reset_state) the simulation takes the logged servo commands, through the
/// actuation delay and lag of the parameters, for `horizon` seconds; the error is each
/// compared signal minus its logged value, divided by that signal's standard deviation over
/// the log, so that signals of different units weigh alike.
class LogReplay {
 public:
  /// @param env_id      An environment of any kind; its ServosEnv is replayed.
  /// @param options     Its fixed options (action_delay and action_lag_min = _max become
  ///                    the actuation's unless fitted).
  /// @throws RobotLogError when the log lacks a signal replay needs (servo commands, servo
  ///         measurements, the pitch rate: a record file of a pendulum or velocity task), is
  ///         irregular, or its period does not divide the environment's step (wrong
  ///         frequency), or is too short for one replay, or the robot is down in every
  ///         replay. Replays where the robot is down are left out (num_windows_down).
  /// @throws std::invalid_argument on an unknown id or a bad option.
  LogReplay(const std::string& env_id, const EnvOptions& options, const RobotLog& log,
            const ReplaySettings& settings, int max_delay_steps, double max_lag);

  /// The root mean square of the normalised errors over every `window_stride`-th replay
  /// (a quicker look: a coarse search); the errors themselves in `residuals` when given,
  /// replay after replay. The replays run on kReplayWorkers threads.
  double rmse(const ParameterValues& values, std::vector<double>* residuals = nullptr,
              std::size_t window_stride = 1) const;

  /// The gyroscope's pitch-rate bias [rad/s] measured without replaying: the mean of the
  /// logged pitch rate minus the logged pitch's central difference (the attitude is
  /// unbiased: the IMU's filter corrects it with the accelerometer), and its standard error
  /// from the means of 0.2 s blocks. Replays see a bias poorly: it shifts one signal of
  /// eight by a constant, less than the start states' own errors.
  std::pair<double, double> pitch_rate_bias() const;

  std::size_t num_windows() const { return window_starts_.size(); }
  /// Replays whose start moved off tire slip (ReplaySettings::slip_threshold).
  std::size_t num_windows_moved_off_slip() const { return windows_moved_off_slip_; }
  /// Replays left out because the robot was down (its base tilted beyond 1 rad) in them: a
  /// robot's log may hold a fall, and a lying robot is not the one to identify.
  std::size_t num_windows_down() const { return windows_down_; }
  /// The errors of one replay in `residuals`, which lists replay after replay.
  std::size_t residuals_per_window() const {
    return static_cast<std::size_t>(horizon_steps_) * kNumReplaySignals;
  }
  /// The environment's step [s], and log cycles per step.
  double timestep() const { return timestep_; }

 private:
  /// The environment options and actuation of one evaluation.
  struct Case {
    EnvOptions options;
    int delay = 0;
    double lag = 0.0;
    double pitch_rate_bias = 0.0;  ///< [rad/s]
  };
  Case make_case(const ParameterValues& values) const;
  /// The errors of the replay from `start` in `errors` (residuals_per_window() of them).
  void replay_window(ServosEnv& servos, const Case& replay, std::size_t start,
                     std::span<double> errors) const;

  struct Sample {
    ResetState state;
    /// d(state's base linear velocity)/d(measured pitch rate) [m/rad]: removing a gyroscope
    /// bias b from the pitch rate moves the no-slip base velocity by -b times it.
    Eigen::Vector3d velocity_per_pitch_rate = Eigen::Vector3d::Zero();
    ServoAction command{};  ///< The servo commands sent at this cycle.
    std::array<double, kNumReplaySignals> signals{};
  };

  std::string env_id_;
  EnvOptions options_;
  double timestep_ = 0.0;
  int horizon_steps_ = 0;
  int fixed_delay_ = 0;
  double fixed_lag_ = 0.0;
  std::vector<Sample> samples_;
  std::array<double, kNumReplaySignals> scales_{};
  std::vector<std::size_t> window_starts_;
  std::size_t windows_down_ = 0;
  std::size_t windows_moved_off_slip_ = 0;
  std::size_t lag_warmup_ = 0;
};

}  // namespace upkie_rl
