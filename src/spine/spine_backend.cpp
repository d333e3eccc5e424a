#include "spine/spine_backend.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <thread>

#include "sim/servo_command_fields.hpp"
#include "spine/observation_reader.hpp"
#include "spine/servo_action_message.hpp"
#include "spine/spine_error.hpp"

namespace upkie_rl {
namespace {

/// Sleeps `delay` seconds in slices of at most 50 ms; false as soon as `interrupt` is set.
bool sleep_unless_interrupted(double delay, const std::atomic<bool>* interrupt) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(delay);
  while (std::chrono::steady_clock::now() < end) {
    if (interrupt != nullptr && interrupt->load()) return false;
    std::this_thread::sleep_for(std::min<std::chrono::duration<double>>(
        end - std::chrono::steady_clock::now(), std::chrono::milliseconds(50)));
  }
  return interrupt == nullptr || !interrupt->load();
}

SharedMemory open_with_retries(const SpineBackendConfig& config) {
  SharedMemory::validate_name(config.shm_name);
  if (config.open_tries < 1) throw SpineError("open_tries must be at least 1");
  std::string last_reason;
  for (int attempt = 1; attempt <= config.open_tries; ++attempt) {
    try {
      return SharedMemory::open(config.shm_name);
    } catch (const SpineError& error) {
      last_reason = error.what();
    }
    if (attempt < config.open_tries) {
      spdlog::info("waiting for spine {} (attempt {} / {})", config.shm_name, attempt,
                   config.open_tries);
      if (!sleep_unless_interrupted(config.open_retry_delay, config.open_interrupt)) {
        throw SpineError("interrupted while waiting for spine " + config.shm_name +
                         " (SIGINT or SIGTERM)");
      }
    }
  }
  throw SpineError("spine " + config.shm_name + " did not respond after " +
                   std::to_string(config.open_tries) + " attempts (" + last_reason +
                   "); is `upkie-rl spine` running?");
}

/// Polls for at most this long with yields before sleeping between polls.
constexpr auto kSpinDuration = std::chrono::microseconds(200);
constexpr auto kPollSleep = std::chrono::microseconds(20);

}  // namespace

SpineBackend::SpineBackend(const SpineBackendConfig& config)
    : config_(config), memory_(open_with_retries(config)), unpacker_(memory_.max_payload_size()) {
  if (!(config.agent_frequency > 0.0 && std::isfinite(config.agent_frequency))) {
    throw SpineError("agent_frequency must be positive and finite");
  }
  if (!(config.request_timeout > 0.0)) throw SpineError("request_timeout must be positive");
}

SpineBackend::~SpineBackend() {
  try {
    stop();
  } catch (const std::exception& error) {
    spdlog::debug("spine backend: stop at destruction failed: {}", error.what());
  }
}

void SpineBackend::wait_for_spine() {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const auto deadline = start + std::chrono::duration_cast<Clock::duration>(
                                    std::chrono::duration<double>(config_.request_timeout));
  for (;;) {
    const std::uint32_t request = memory_.request();
    if (request == static_cast<std::uint32_t>(Request::kNone)) return;
    if (request == static_cast<std::uint32_t>(Request::kError)) {
      memory_.set_request(Request::kNone);
      throw SpineError("invalid request, is the spine started?");
    }
    const auto now = Clock::now();
    if (now > deadline) {
      throw SpineTimeoutError("spine did not process request within " +
                              std::to_string(std::lround(config_.request_timeout * 1e3)) +
                              " ms, is it stopped?");
    }
    if (now - start < kSpinDuration) {
      std::this_thread::yield();
    } else {
      std::this_thread::sleep_for(kPollSleep);
    }
  }
}

void SpineBackend::send(Request request) {
  memory_.write_payload({buffer_.data(), buffer_.size()});
  memory_.set_request(request);
}

const Observation& SpineBackend::read_observation_payload(bool after_reset) {
  // A spine that writes no `time` (the robot's) gets the agent's clock instead.
  const double previous_time = observation_.time;
  observation_.time = std::numeric_limits<double>::quiet_NaN();
  // An absent optional key keeps its value: NaN tells a required one was not written.
  Eigen::Vector3d& acceleration = observation_.imu.linear_acceleration;
  if (config_.require_imu_acceleration) acceleration.x() = std::numeric_limits<double>::quiet_NaN();
  read_observation(unpacker_.unpack(memory_.payload()), observation_);
  if (std::isnan(observation_.time)) {
    observation_.time = after_reset ? 0.0 : previous_time + agent_timestep();
  }
  if (config_.require_imu_acceleration && !acceleration.allFinite()) {
    throw SpineError(
        "spine observation key 'imu.linear_acceleration' is missing or not finite: the policy "
        "observes the IMU's acceleration (observe_acceleration), which this spine does not "
        "write");
  }
  return observation_;
}

void SpineBackend::stop() {
  wait_for_spine();
  memory_.set_request(Request::kStop);
}

void SpineBackend::force_stop() { memory_.set_request(Request::kStop); }

const Observation& SpineBackend::reset(const ResetState& state) {
  stop();
  write_start_config_msgpack(state, config_.start_parameters, buffer_);
  wait_for_spine();
  send(Request::kStart);
  wait_for_spine();
  next_action_time_.reset();
  return read_observation_payload(true);
}

bool SpineBackend::regulate(bool action_just_sent) {
  using Clock = std::chrono::steady_clock;
  const auto period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / config_.agent_frequency));
  const auto now = Clock::now();
  if (!next_action_time_) {
    // An episode's first action leaves at once; its tick is a period after it left.
    next_action_time_ = action_just_sent ? now + period : now;
  } else if (*next_action_time_ < now - period) {
    next_action_time_ = now;  // late by more than a period: no burst
  }
  const bool early = now < *next_action_time_;
  std::this_thread::sleep_until(*next_action_time_);
  *next_action_time_ += period;
  return early;
}

const Observation& SpineBackend::step(const ServoAction& action) {
  // The robot gets finite values only: NaN where the field allows it ("no position loop"),
  // never the +inf maximum torque a simulation accepts.
  validate_servo_action(action, ServoActionTarget::kRobot);
  write_servo_action_msgpack(action, buffer_);
  const bool fresh = config_.regulate_frequency && config_.fresh_observation;
  if (config_.regulate_frequency && !fresh) regulate(false);
  wait_for_spine();
  send(Request::kAction);
  // A loop already late at its tick skips the second request: the action's own reply is
  // then as fresh, and another spine cycle would only make the loop later.
  if (fresh && regulate(true)) {
    wait_for_spine();
    send(Request::kAction);  // the same action again: its reply is the tick's observation
  }
  wait_for_spine();
  return read_observation_payload(false);
}

}  // namespace upkie_rl
