#include "identify/log_replay.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>
#include <thread>

#include "base/number_text.hpp"
#include "envs/kinds/servos_env.hpp"
#include "envs/registry/env_factory.hpp"
#include "envs/wrappers/env_wrapper.hpp"
#include "identify/measured_reset_state.hpp"
#include "identify/tire_slip_evidence.hpp"
#include "sim/physics_config.hpp"
#include "sim/servo_command_fields.hpp"
#include "sim/servo_target_lag.hpp"
#include "sim/simulation.hpp"

namespace upkie_rl {

namespace {

/// Smallest scale of each signal: a log where one barely moves must not blow its errors up.
constexpr std::array<double, kNumReplaySignals> kMinimumScales = {0.01,  0.05,  0.5,   0.5,
                                                                  0.005, 0.005, 0.005, 0.005};
/// Normalised error of each signal after the simulation diverged.
constexpr double kDivergedError = 10.0;

std::array<double, kNumReplaySignals> replay_signals(const Observation& observation) {
  return {observation.base_orientation.pitch,     observation.base_orientation.angular_velocity.y(),
          observation.servo[kLeftWheel].velocity, observation.servo[kRightWheel].velocity,
          observation.servo[kLeftHip].position,   observation.servo[kLeftKnee].position,
          observation.servo[kRightHip].position,  observation.servo[kRightKnee].position};
}

ServosEnv& find_servos_env(Env& env) {
  Env* current = &env;
  while (current != nullptr) {
    if (auto* servos = dynamic_cast<ServosEnv*>(current)) return *servos;
    auto* wrapper = dynamic_cast<EnvWrapper*>(current);
    current = wrapper != nullptr ? &wrapper->inner() : nullptr;
  }
  throw std::invalid_argument("identify: the environment has no servos to replay commands on");
}

bool is_actuation_option(const std::string& name) {
  return name == "action_delay" || name == "action_lag_min" || name == "action_lag_max";
}

/// The log's cycles taken every `stride`, with the environment's step.
std::size_t decimation(const RobotLog& log, double timestep, const std::string& env_id) {
  const double period = log.period();
  const double ratio = timestep / period;
  const double stride = std::round(ratio);
  if (stride < 1.0 || std::abs(ratio - stride) > 0.01 * stride) {
    throw RobotLogError(log.format + " " + log.name + ": wrong frequency: cycles every " +
                        shortest_text(1e3 * period) + " ms (" + shortest_text(1.0 / period) +
                        " Hz), " + env_id + " steps every " + shortest_text(1e3 * timestep) +
                        " ms: not a whole number of cycles per step (set its frequency option)");
  }
  return static_cast<std::size_t>(stride);
}

/// Whether two commands differ, a NaN position equal to a NaN position.
bool commands_differ(const ServoAction& a, const ServoAction& b) {
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    for (const ServoCommandField& field : kServoCommandFields) {
      const double x = a[servo].*field.member;
      const double y = b[servo].*field.member;
      if (x != y && !(std::isnan(x) && std::isnan(y))) return true;
    }
  }
  return false;
}

/// The replays of a log.
struct ReplayStarts {
  std::vector<std::size_t> starts;
  std::size_t down = 0;  ///< Replays left out: the robot was down in them.
};

/// Whether the replay from sample `start` keeps the robot up (`up` as in replay_starts).
bool replay_is_up(const std::vector<std::size_t>& up, std::size_t start, std::size_t horizon) {
  return start + horizon + 1 < up.size() && up[start + horizon + 1] - up[start] == horizon + 1;
}

/// Every `spacing`-th sample from `first` that leaves a whole replay of `horizon` steps in
/// the log, and in which the robot is up throughout (`up[i]`: how many of the samples before
/// i have the robot up; one more entry than samples), at most `max_windows` of them spread
/// evenly over the log.
ReplayStarts replay_starts(std::size_t first, const std::vector<std::size_t>& up,
                           std::size_t horizon, std::size_t spacing, std::size_t max_windows) {
  ReplayStarts replays;
  for (std::size_t start = first; start + horizon + 1 < up.size(); start += spacing) {
    if (replay_is_up(up, start, horizon)) {
      replays.starts.push_back(start);
    } else {
      ++replays.down;
    }
  }
  if (replays.starts.size() <= max_windows) return replays;
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < max_windows; ++i)
    kept.push_back(replays.starts[i * replays.starts.size() / max_windows]);
  replays.starts = std::move(kept);
  return replays;
}

/// Slides each of `starts` forward by less than `reach` samples to the first one whose
/// `evidence` of tire slip is at most `threshold` and whose replay keeps the robot up, or to
/// the least evidence of those when none is under it. Returns how many moved.
std::size_t slide_off_slip(std::vector<std::size_t>& starts, std::span<const double> evidence,
                           const std::vector<std::size_t>& up, std::size_t horizon,
                           std::size_t reach, double threshold) {
  std::size_t moved = 0;
  for (std::size_t& start : starts) {
    std::size_t best = start;
    for (std::size_t candidate = start; candidate < start + reach; ++candidate) {
      if (candidate >= evidence.size() || !replay_is_up(up, candidate, horizon)) break;
      if (evidence[candidate] < evidence[best]) best = candidate;
      if (evidence[candidate] <= threshold) {
        best = candidate;
        break;
      }
    }
    moved += best != start ? 1 : 0;
    start = best;
  }
  return moved;
}

void require_signals(const RobotLog& log) {
  const auto missing = [&](const char* what) {
    throw RobotLogError(
        log.format + " " + log.name + ": no " + what +
        ": identification replays the servo commands and compares joint and IMU "
        "measurements (record with `upkie-rl spine --log` or the robot's spine log, "
        "or `rollout --record` on a servos environment)");
  };
  if (!log.signals.servo_commands) missing("servo commands (action.<joint>.<field> columns)");
  if (!log.signals.servo_measurements) missing("servo measurements (<joint>.position, .velocity)");
  if (!log.signals.pitch_rate) missing("base pitch rate");
}

}  // namespace

std::size_t agent_phase(const RobotLog& log, std::size_t stride) {
  std::vector<std::size_t> changes(stride, 0);
  for (std::size_t i = 1; i < log.cycles.size(); ++i) {
    if (commands_differ(log.cycles[i].command, log.cycles[i - 1].command)) ++changes[i % stride];
  }
  const auto most = std::max_element(changes.begin(), changes.end());
  return *most == 0 ? 0 : static_cast<std::size_t>(most - changes.begin());
}

LogReplay::LogReplay(const std::string& env_id, const EnvOptions& options, const RobotLog& log,
                     const ReplaySettings& settings, int max_delay_steps, double max_lag)
    : env_id_(env_id) {
  require_signals(log);
  log.check_regular();
  double lag_min = 0.0;
  double lag_max = 0.0;
  for (const auto& [name, value] : options) {
    if (name == "action_delay_max") {
      throw std::invalid_argument(
          "identify: action_delay_max draws a delay per episode; a log is replayed with one "
          "delay, set action_delay");
    }
    if (name == "action_delay_time") {
      throw std::invalid_argument(
          "identify: action_delay_time: give the replay's delay in the environment's steps, "
          "action_delay");
    }
    if (!is_actuation_option(name)) {
      options_.emplace_back(name, value);
      continue;
    }
    const std::optional<double> parsed = number_from_text<double>(value);
    if (!parsed || !std::isfinite(*parsed)) {
      throw std::invalid_argument("identify: option " + name + "=" + value +
                                  ": not a finite number");
    }
    const double number = *parsed;
    if (name == "action_delay") {
      fixed_delay_ = static_cast<int>(number);
    } else {
      (name == "action_lag_min" ? lag_min : lag_max) = number;
    }
  }
  if (lag_min != lag_max) {
    throw std::invalid_argument(
        "identify: action_lag_min and action_lag_max must be equal (one "
        "time constant), got " +
        shortest_text(lag_min) + " and " + shortest_text(lag_max));
  }
  fixed_lag_ = lag_max;
  std::unique_ptr<Env> probe = make_env(env_id, options_);
  const RobotModel& model = find_servos_env(*probe).model();
  timestep_ = probe->timestep();
  const std::size_t stride = decimation(log, timestep_, env_id);
  std::vector<std::size_t> up{0};  // samples with the robot up before each index
  std::vector<std::size_t> sample_cycles;
  for (std::size_t i = agent_phase(log, stride); i < log.cycles.size(); i += stride) {
    const LoggedCycle& cycle = log.cycles[i];
    sample_cycles.push_back(i);
    up.push_back(up.back() + (robot_is_down(cycle.observation) ? 0 : 1));
    Sample& sample = samples_.emplace_back();
    sample.state = measured_reset_state(model, cycle.observation);
    Observation turned = cycle.observation;  // the state is linear in the pitch rate
    turned.base_orientation.angular_velocity.y() += 1.0;
    sample.velocity_per_pitch_rate =
        measured_reset_state(model, turned).linear_velocity_base_to_world_in_world -
        sample.state.linear_velocity_base_to_world_in_world;
    sample.signals = replay_signals(cycle.observation);
    sample.command = cycle.command;
  }
  // Each signal's standard deviation over the log.
  for (std::size_t k = 0; k < kNumReplaySignals; ++k) {
    double sum = 0.0;
    double sum_squares = 0.0;
    for (const Sample& sample : samples_) {
      sum += sample.signals[k];
      sum_squares += sample.signals[k] * sample.signals[k];
    }
    const double n = static_cast<double>(samples_.size());
    const double variance = std::max(0.0, sum_squares / n - (sum / n) * (sum / n));
    scales_[k] = std::max(kMinimumScales[k], std::sqrt(variance));
  }
  horizon_steps_ = std::max(1, static_cast<int>(std::lround(settings.horizon / timestep_)));
  const auto spacing = std::max<std::size_t>(
      1, static_cast<std::size_t>(std::lround(settings.window_spacing / timestep_)));
  // The lag's filter starts five time constants before a window, from the log's commands.
  lag_warmup_ =
      static_cast<std::size_t>(std::ceil(5.0 * std::max(max_lag, fixed_lag_) / timestep_));
  const std::size_t first =
      static_cast<std::size_t>(std::max(max_delay_steps, fixed_delay_)) + lag_warmup_;
  ReplayStarts replays = replay_starts(first, up, static_cast<std::size_t>(horizon_steps_), spacing,
                                       settings.max_windows);
  window_starts_ = std::move(replays.starts);
  windows_down_ = replays.down;
  if (settings.slip_threshold > 0.0 && logs_accelerometer(log)) {
    const std::vector<double> evidence =
        tire_slip_evidence(model, log, sample_cycles, settings.slip_span, PhysicsConfig{}.gravity);
    windows_moved_off_slip_ =
        slide_off_slip(window_starts_, evidence, up, static_cast<std::size_t>(horizon_steps_),
                       std::max<std::size_t>(1, spacing / 2), settings.slip_threshold);
  }
  if (window_starts_.empty() && windows_down_ > 0) {
    throw RobotLogError(log.format + " " + log.name + ": the robot is down (its base tilted " +
                        "beyond " + shortest_text(kFallenTilt) +
                        " rad) in every replay: nothing to identify a standing robot from");
  }
  if (window_starts_.empty()) {
    throw RobotLogError(log.format + " " + log.name + ": " + shortest_text(log.duration()) +
                        " s is too short for one replay of " + shortest_text(settings.horizon) +
                        " s after the actuation's warm-up");
  }
}

std::pair<double, double> LogReplay::pitch_rate_bias() const {
  const std::size_t block = std::max<std::size_t>(1, std::lround(0.2 / timestep_));
  std::vector<double> block_means;
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 1; i + 1 < samples_.size(); ++i) {
    const double pitch_change =
        (samples_[i + 1].signals[0] - samples_[i - 1].signals[0]) / (2.0 * timestep_);
    sum += samples_[i].signals[1] - pitch_change;
    if (++count == block) {
      block_means.push_back(sum / static_cast<double>(count));
      sum = 0.0;
      count = 0;
    }
  }
  if (block_means.size() < 2) return {0.0, std::numeric_limits<double>::infinity()};
  double mean = 0.0;
  for (const double value : block_means) mean += value;
  mean /= static_cast<double>(block_means.size());
  double variance = 0.0;
  for (const double value : block_means) variance += (value - mean) * (value - mean);
  const double n = static_cast<double>(block_means.size());
  return {mean, std::sqrt(variance / (n - 1.0) / n)};
}

LogReplay::Case LogReplay::make_case(const ParameterValues& values) const {
  Case replay{options_, fixed_delay_, fixed_lag_, 0.0};
  for (const auto& [parameter, value] : values) {
    if (parameter->name == "imu_gyroscope_bias_fixed_y") replay.pitch_rate_bias = value;
    if (parameter->name == "action_delay") {
      replay.delay = static_cast<int>(std::lround(value));
    } else if (parameter->name == "action_lag") {
      replay.lag = value;
    } else {
      replay.options.emplace_back(std::string(parameter->name), shortest_text(value));
    }
  }
  return replay;
}

void LogReplay::replay_window(ServosEnv& servos, const Case& replay, std::size_t start,
                              std::span<double> errors) const {
  // The environments' actuation law (ActionLag): the delayed command through the filter's
  // mean over each step.
  const ServoTargetLag lag = ServoTargetLag::step_mean(replay.lag, timestep_);
  ServoAction filtered{};
  ServoAction applied{};
  const auto actuate = [&](const ServoAction& sent) -> const ServoAction& {
    if (!lag.any()) return sent;
    lag.step(sent, filtered, applied);
    return applied;
  };
  ResetState state = samples_[start].state;  // what the gyroscope measured, less its bias
  state.angular_velocity_base_in_base.y() -= replay.pitch_rate_bias;
  state.linear_velocity_base_to_world_in_world -=
      replay.pitch_rate_bias * samples_[start].velocity_per_pitch_rate;
  servos.reset_servos_to(state, 0);
  const auto delay = static_cast<std::size_t>(replay.delay);
  const std::size_t warmup = std::min(lag_warmup_, start - delay);
  filtered = samples_[start - delay - warmup].command;
  for (std::size_t j = start - warmup; j < start; ++j) actuate(samples_[j - delay].command);
  bool diverged = false;
  for (int step = 0; step < horizon_steps_; ++step) {
    const std::size_t index = start + static_cast<std::size_t>(step);
    const ServoAction& command = actuate(samples_[index - delay].command);
    std::array<double, kNumReplaySignals> predicted{};
    if (!diverged) {
      try {
        predicted = replay_signals(servos.step_servos(command));
      } catch (const SimulationDivergedError&) {
        diverged = true;
      }
    }
    for (std::size_t k = 0; k < kNumReplaySignals; ++k) {
      errors[static_cast<std::size_t>(step) * kNumReplaySignals + k] =
          diverged ? kDivergedError : (predicted[k] - samples_[index + 1].signals[k]) / scales_[k];
    }
  }
}

double LogReplay::rmse(const ParameterValues& values, std::vector<double>* residuals,
                       std::size_t window_stride) const {
  const Case replay = make_case(values);
  std::vector<std::size_t> starts;
  for (std::size_t i = 0; i < window_starts_.size(); i += std::max<std::size_t>(1, window_stride)) {
    starts.push_back(window_starts_[i]);
  }
  const std::size_t block = residuals_per_window();
  std::vector<double> errors(starts.size() * block);
  // A fixed number of workers, each with its own environment and every kReplayWorkers-th
  // replay: the same replays on the same environments whatever the machine, so the same
  // result. An error in a worker is rethrown here.
  std::array<std::exception_ptr, kReplayWorkers> failures{};
  const auto work = [&](std::size_t worker) {
    try {
      std::unique_ptr<Env> env = make_env(env_id_, replay.options);
      ServosEnv& servos = find_servos_env(*env);
      for (std::size_t w = worker; w < starts.size(); w += kReplayWorkers) {
        replay_window(servos, replay, starts[w], std::span(errors).subspan(w * block, block));
      }
    } catch (...) {
      failures[worker] = std::current_exception();
    }
  };
  std::vector<std::thread> threads;
  for (std::size_t worker = 1; worker < kReplayWorkers; ++worker)
    threads.emplace_back(work, worker);
  work(0);
  for (std::thread& thread : threads) thread.join();
  for (const std::exception_ptr& failure : failures) {
    if (failure) std::rethrow_exception(failure);
  }
  double sum_squares = 0.0;
  for (const double error : errors) sum_squares += error * error;
  if (residuals != nullptr) *residuals = std::move(errors);
  return std::sqrt(sum_squares / static_cast<double>(starts.size() * block));
}

}  // namespace upkie_rl
