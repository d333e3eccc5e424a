#pragma once
/// @file
/// The agent side of the spine link as a Simulation backend: environments built on it
/// drive a spine process (ours, or the real robot's) instead of an in-process simulator.

#include <atomic>
#include <chrono>
#include <msgpack.hpp>
#include <optional>
#include <string>

#include "base/option_table.hpp"
#include "sim/simulation.hpp"
#include "spine/payload_unpacker.hpp"
#include "spine/reset_config.hpp"
#include "spine/shared_memory.hpp"

namespace upkie_rl {

/// Settings of a SpineBackend.
struct SpineBackendConfig {
  std::string shm_name = "/upkie";  ///< Shared-memory name of the spine.
  double agent_frequency = 200.0;   ///< Agent steps per second [Hz]; agent_timestep = 1/f.
  /// Sleep before each action so that actions leave at agent_frequency (needed with a
  /// real-time spine, like the public environments' rate limiter). Off for a spine that
  /// advances on request, where it would only slow the agent down.
  bool regulate_frequency = true;
  /// With regulate_frequency: send the action as soon as it is given, sleep until the next
  /// tick, then send it again and return the reply of that second request, so the policy
  /// acts on an observation one spine cycle old instead of a whole agent period old.
  /// Why: sleeping before the send (the public environments' order) applies each action
  /// one period after the observation it was computed from, a delay no simulation trains
  /// with; at 50 Hz the from-scratch velocity policy's yaw tracking went from 0.056 to
  /// 0.24-0.33 rad/s and it fell in a standing turn on the real-time MuJoCo spine. The
  /// repeated action changes nothing (spines merge actions); it costs one spine cycle per
  /// step, skipped when the loop is already late at the tick (the 200 Hz pendulum runner
  /// on a loaded 2-core machine otherwise tripped the supervisor's overrun limit in 1 of
  /// 4 runs). Only for a real-time spine: one that advances on request would step twice.
  bool fresh_observation = true;
  /// Refuse observations without `imu.linear_acceleration` (a SpineError naming the key at
  /// reset or step). Why: the reader leaves an optional key that a spine does not write as it
  /// was, so a policy that observes the IMU's acceleration (observe_acceleration) would run
  /// on zeros, silently, on a spine without an accelerometer (a mock spine). Set from the
  /// task by spine_backend_config().
  bool require_imu_acceleration = false;
  /// How long a request may stay unprocessed before a SpineTimeoutError [s].
  double request_timeout = 0.1;
  int open_tries = 10;            ///< Attempts at opening the shared memory.
  double open_retry_delay = 1.0;  ///< Pause between two attempts [s].
  /// When given and set (a SIGINT or SIGTERM handler's flag), waiting for the spine ends at
  /// once: up to open_tries seconds of attempts would otherwise ignore Ctrl-C.
  const std::atomic<bool>* open_interrupt = nullptr;
  SpineStartParameters start_parameters;  ///< Sent with every Start.

  /// Declares the options shm_name, regulate_frequency, request_timeout and open_tries
  /// (spine_backend_options.cpp); the agent frequency is the environment's `frequency`.
  void declare_options(OptionTable& table);
};

/// Talks to a spine through its shared memory (spine.md section 2): reset() is stop()
/// then start(configuration with the reset state); step() sends the servo action and
/// returns the observation of that step, decoded into the typed Observation. When the
/// spine writes no `time` (the robot's spine), the observation's time counts agent steps
/// from the reset. Once warmed up, a step allocates nothing. Not thread-safe. The
/// destructor stops the spine.
class SpineBackend final : public Simulation {
 public:
  /// Opens the spine's shared memory, trying `open_tries` times `open_retry_delay` apart.
  /// @throws SpineError "spine <name> did not respond ..." when it never appears, or
  ///         "interrupted while waiting for spine <name>" when open_interrupt is set.
  explicit SpineBackend(const SpineBackendConfig& config = {});
  ~SpineBackend() override;
  SpineBackend(const SpineBackend&) = delete;
  SpineBackend& operator=(const SpineBackend&) = delete;

  /// Stops the spine, then starts it with `state`; returns its first observation.
  /// @throws SpineTimeoutError when the spine does not answer within request_timeout.
  /// @throws SpineError on an Error reply or a malformed observation.
  const Observation& reset(const ResetState& state) override;

  /// Sends `action` and returns the observation of that step.
  /// @throws InvalidCommandError on a non-finite velocity, torque or gain (NaN position
  ///         is allowed), before anything is sent.
  /// @throws SpineTimeoutError, SpineError as reset().
  const Observation& step(const ServoAction& action) override;

  const Observation& observation() const override { return observation_; }
  double agent_timestep() const override { return 1.0 / config_.agent_frequency; }

  /// Asks the spine to stop its actuators (does not wait for completion).
  void stop();

  /// Writes the Stop request over whatever request is pending, without waiting: what an
  /// agent leaving a silent spine does, so that a spine that comes back (a frozen process
  /// resumed) finds Stop rather than a stale action.
  void force_stop();

  const SpineBackendConfig& config() const { return config_; }

 private:
  void wait_for_spine();
  void send(Request request);
  const Observation& read_observation_payload(bool after_reset);
  /// Sleeps until the next tick of agent_frequency; an episode's first tick is now, or a
  /// period after an action sent just before. Returns whether the tick was still ahead.
  bool regulate(bool action_just_sent);

  SpineBackendConfig config_;
  SharedMemory memory_;
  PayloadUnpacker unpacker_;
  msgpack::sbuffer buffer_;
  Observation observation_;
  std::optional<std::chrono::steady_clock::time_point> next_action_time_;
};

}  // namespace upkie_rl
