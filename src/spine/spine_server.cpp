#include "spine/spine_server.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <thread>
#include <utility>

#include "sim/observation_dict.hpp"
#include "spine/reset_config.hpp"
#include "spine/servo_action_message.hpp"
#include "spine/spine_error.hpp"

namespace upkie_rl {
namespace {

/// In on-request mode, polls spin (yielding) this many idle cycles before sleeping, which
/// keeps the reply latency low while the agent is busy without burning a core when not.
constexpr int kSpinningIdleCycles = 2000;
constexpr auto kIdleSleep = std::chrono::microseconds(50);

}  // namespace

SpineServer::SpineServer(Simulation& simulation, const SpineServerConfig& config,
                         BrakeStep brake_step, SettingsSetter set_settings)
    : simulation_(simulation),
      config_(config),
      brake_step_(std::move(brake_step)),
      set_settings_(std::move(set_settings)),
      memory_(SharedMemory::create(config.shm_name, config.shm_size, config.shm_mode)),
      machine_(config.nb_stop_cycles),
      unpacker_(memory_.max_payload_size()),
      action_(spine_default_servo_action()),
      actuation_(config.actuation) {
  publish_state();
  if (config.observation_delay_steps < 0 || config.observation_delay_steps > 100000) {
    throw SpineError("observation delay must be in [0, 100000] steps, got " +
                     std::to_string(config.observation_delay_steps));
  }
  if (!(config.cycle_jitter >= 0.0 && std::isfinite(config.cycle_jitter))) {
    throw SpineError("cycle jitter must be finite and >= 0");
  }
  history_.resize(static_cast<std::size_t>(config.observation_delay_steps) + 1);
  if (config.real_time && !(config.frequency > 0.0 && std::isfinite(config.frequency))) {
    throw SpineError("spine frequency must be positive and finite, got " +
                     std::to_string(config.frequency));
  }
  for (ServoCommand& command : stop_action_) {
    command = ServoCommand{std::numeric_limits<double>::quiet_NaN(),
                           0.0,
                           0.0,
                           0.0,
                           config.brake_kd_scale,
                           config.brake_maximum_torque};
  }
}

void SpineServer::interrupt() {
  machine_.on_interrupt();
  publish_state();
}

void SpineServer::cycle() {
  nb_cycles_.fetch_add(1, std::memory_order_relaxed);
  if (machine_.is_over()) return;
  try {
    if (const auto request = machine_.on_cycle_beginning(memory_.request())) {
      memory_.set_request(*request);
    }
    if (machine_.start_ignored()) spdlog::warn("spine: Start request while started, ignored");
    process_state();
    if (const auto request = machine_.on_cycle_end()) memory_.set_request(*request);
  } catch (const SimulationDivergedError& exception) {
    // A diverged simulation refuses every step until a reset, and a shutting-down spine
    // resets nothing: the Shutdown cycles send it no stops (they would throw each cycle).
    simulation_ready_ = false;
    fail(exception.what());
  } catch (const std::exception& exception) {
    fail(exception.what());
  }
  publish_state();
}

void SpineServer::fail(const std::string& message) {
  if (machine_.state() == SpineState::kShutdown) {
    // The shutdown itself failed: its stop cycles cannot run, and retrying the cycle would
    // fail again every cycle and never reach Over (nor honour a signal, which only asks
    // for the Shutdown already under way).
    spdlog::error("spine: {} while shutting down; stopping at once", message);
    if (error_.empty()) error_ = message;
    machine_.abort();
    return;
  }
  error_ = message;
  spdlog::error("spine: {}; shutting down", error_);
  machine_.on_interrupt();
}

void SpineServer::process_state() {
  switch (machine_.state()) {
    case SpineState::kReset:
      reset_from_payload();
      write_observation();
      break;
    case SpineState::kStep:
      step_from_payload();
      advance_sent();
      write_observation();
      break;
    case SpineState::kIdle:
      if (config_.real_time) advance_sent();
      break;
    case SpineState::kSendStops:
    case SpineState::kShutdown:
      if (config_.real_time && simulation_ready_) {
        if (brake_step_) {
          brake_step_();
          remember_observation();
          nb_simulation_steps_.fetch_add(1, std::memory_order_relaxed);
          if (observer_) observer_(simulation_.observation(), stop_action_, false);
        } else {
          advance(stop_action_, stop_action_);  // the spine's own stops are not delayed
        }
      }
      break;
    case SpineState::kOver:
      break;
  }
}

void SpineServer::reset_from_payload() {
  // The configuration is replaced, not merged (spine.md section 4).
  configuration_.clear();
  configuration_.update(unpacker_.unpack(memory_.payload()));
  const ResetState state = reset_state_from_config(configuration_);
  const SpineStartSettings settings{
      servo_gains_from_config(configuration_, config_.default_servo_gains),
      imu_uncertainty_from_config(configuration_)};

  // The action is reset to the defaults, which also fixes every field's type to float.
  action_dictionary_.clear();
  action_ = spine_default_servo_action();
  write_servo_action_msgpack(action_, buffer_);
  action_dictionary_.update(unpacker_.unpack({buffer_.data(), buffer_.size()}));

  actuation_.reset(action_);
  if (set_settings_) set_settings_(settings);
  simulation_.reset(state);
  simulation_ready_ = true;
  std::fill(history_.begin(), history_.end(), simulation_.observation());
  if (observer_) observer_(simulation_.observation(), action_, true);
}

void SpineServer::step_from_payload() {
  action_dictionary_.update(unpacker_.unpack(memory_.payload()));
  read_servo_action(action_dictionary_, action_, &config_.maximum_torques);
}

void SpineServer::remember_observation() {
  history_[history_next_] = simulation_.observation();
  history_next_ = (history_next_ + 1) % history_.size();
}

void SpineServer::advance_sent() { advance(actuation_.apply(action_), action_); }

void SpineServer::advance(const ServoAction& action, const ServoAction& logged) {
  simulation_.step(action);
  remember_observation();
  nb_simulation_steps_.fetch_add(1, std::memory_order_relaxed);
  if (observer_) observer_(simulation_.observation(), logged, false);
}

void SpineServer::write_observation() {
  // The oldest kept: the newest when there is no delay.
  write_observation_msgpack(history_[history_next_], buffer_);
  memory_.write_payload({buffer_.data(), buffer_.size()});
}

void SpineServer::run(const std::atomic<bool>& interrupt) {
  using Clock = std::chrono::steady_clock;
  const auto period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / config_.frequency));
  auto next_cycle = Clock::now();
  int idle_cycles = 0;
  std::mt19937_64 jitter_generator(config_.jitter_seed);
  std::uniform_real_distribution<double> jitter(0.0, config_.cycle_jitter);
  while (!machine_.is_over()) {
    if (interrupt.load(std::memory_order_relaxed)) machine_.on_interrupt();
    const std::uint32_t request = memory_.request();
    const bool had_request = request != static_cast<std::uint32_t>(Request::kNone) &&
                             request != static_cast<std::uint32_t>(Request::kError);
    cycle();
    if (config_.real_time) {
      next_cycle += period;
      const auto now = Clock::now();
      if (next_cycle < now - 10 * period) next_cycle = now;  // fell behind: don't burst
      if (config_.cycle_jitter > 0.0) {
        std::this_thread::sleep_until(next_cycle +
                                      std::chrono::duration_cast<Clock::duration>(
                                          std::chrono::duration<double>(jitter(jitter_generator))));
      } else {
        std::this_thread::sleep_until(next_cycle);
      }
    } else if (had_request || machine_.state() == SpineState::kShutdown) {
      idle_cycles = 0;
    } else if (++idle_cycles < kSpinningIdleCycles) {
      std::this_thread::yield();
    } else {
      std::this_thread::sleep_for(kIdleSleep);
    }
  }
}

}  // namespace upkie_rl
