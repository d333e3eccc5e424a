#pragma once
/// @file
/// The spine process side of the link: a simulation served through shared memory to an
/// agent (ours, or the public `upkie` Python package), with the reference state machine.

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <msgpack.hpp>
#include <string>
#include <vector>

#include "sim/servo_law.hpp"
#include "sim/simulation.hpp"
#include "spine/dictionary.hpp"
#include "spine/payload_unpacker.hpp"
#include "spine/reset_config.hpp"
#include "spine/servo_action_lag.hpp"
#include "spine/shared_memory.hpp"
#include "spine/spine_state_machine.hpp"

namespace upkie_rl {

/// Settings of a SpineServer.
struct SpineServerConfig {
  std::string shm_name = "/upkie";                    ///< POSIX shared-memory name.
  std::size_t shm_size = SharedMemory::kDefaultSize;  ///< [bytes]
  /// Permissions of the shared memory (SharedMemory::create): owner only by default.
  unsigned shm_mode = SharedMemory::kDefaultMode;
  /// True: a real-time loop at `frequency` where the simulation advances every cycle
  /// whatever the agent does (like the robot); give it a simulation whose step() is one
  /// physics step. False: the simulation advances only on Action requests, by one step()
  /// of the simulation (nb_substeps physics steps), as fast as the agent asks.
  bool real_time = true;
  double frequency = 1000.0;  ///< Cycles per second in real-time mode [Hz].
  /// Joint effort limits [N.m]: an action whose maximum_torque leaves [0, effort] is an
  /// error that shuts the spine down, as on the real robot.
  std::array<double, kNumServos> maximum_torques = {16.0, 16.0, 1.7, 16.0, 16.0, 1.7};
  /// Stop command of a stopped joint, when the server has no brake step: velocity 0, no
  /// position term, kd scaled by this.
  double brake_kd_scale = 10.0;
  /// Torque clamp of the stop command [N.m] (the simulation's effort clamp applies on top).
  double brake_maximum_torque = 100.0;
  int nb_stop_cycles = SpineStateMachine::kDefaultNbStopCycles;
  /// Servo gains given to the simulation at a Start whose configuration has no
  /// bullet.torque_control (the configuration is replaced at each Start, not merged).
  ServoGains default_servo_gains{};
  /// Sim-to-real timing: the observation written to the agent is the one of this many
  /// simulation steps ago (the robot's observations are about one pi3hat cycle, ~1 ms, old).
  int observation_delay_steps = 0;
  /// Sim-to-real timing, real-time mode: each cycle starts up to this late, uniformly
  /// drawn, without shifting the schedule [s].
  double cycle_jitter = 0.0;
  std::uint64_t jitter_seed = 0;  ///< Seed of the jitter's draws.
  /// Sim-to-real actuation: the agent's commands reach the simulated servos this late and
  /// this slowly (in simulation steps; the step's duration is the simulation's). The spine
  /// log and the simulation observer see the commands as sent, as a robot's spine logs them.
  ServoActionLagSettings actuation;
};

/// Serves a Simulation over the spine link. Creates the shared memory at construction
/// (removing a stale one) and unlinks it at destruction. Each cycle() reads the request
/// word, runs the state machine, then resets or steps the simulation and writes the
/// observation before clearing the request. An exception in a cycle (malformed, nil,
/// mistyped or oversized message, an invalid command, a diverged simulation) is logged
/// and sends the spine to Shutdown, then Over; it never escapes cycle(). A diverged
/// simulation is not stepped again (no stops in Shutdown), and an exception in Shutdown
/// ends the spine at once (Over), so a failing spine always ends.
class SpineServer {
 public:
  /// Steps the simulation once with every joint braked (e.g. BulletSimulation's
  /// step_braked(), which brakes beyond the servo effort clamp).
  using BrakeStep = std::function<void()>;
  /// Gives the simulation what a Start configuration sets besides the reset state: servo
  /// gains and IMU uncertainty (PhysicsSimulation::set_servo_gains and set_variation).
  using SettingsSetter = std::function<void(const SpineStartSettings&)>;

  /// @param simulation Backend served; must outlive the server.
  /// @param brake_step How stopped joints are stepped in real-time mode; when empty, the
  ///        simulation steps with a stop command per joint (position NaN, velocity 0,
  ///        kd_scale brake_kd_scale, maximum_torque brake_maximum_torque), which the
  ///        simulation's servo law clamps to the joint effort.
  /// @param set_settings Called at each Start, before the reset, with bullet.torque_control's
  ///        kp and kd (or SpineServerConfig::default_servo_gains) and
  ///        bullet.imu_uncertainty (zero when absent); when empty, the configuration's are
  ///        ignored.
  /// @throws SpineError when the shared memory cannot be created.
  SpineServer(Simulation& simulation, const SpineServerConfig& config, BrakeStep brake_step = {},
              SettingsSetter set_settings = {});

  /// Called on the cycling thread after each reset and each simulation step with the
  /// simulation's observation, the action the agent sent (the defaults after a reset, the
  /// spine's stops while stopping; what SpineServerConfig::actuation applied may differ)
  /// and whether it was a reset; for viewers and logs. Must not throw.
  using SimulationObserver =
      std::function<void(const Observation& observation, const ServoAction& action, bool reset)>;
  void set_simulation_observer(SimulationObserver observer) { observer_ = std::move(observer); }

  /// Runs one cycle (no waiting).
  void cycle();

  /// Cycles until Over: paced at `frequency` in real-time mode, polling otherwise. Sets
  /// Shutdown as soon as `interrupt` becomes true (a signal handler may set it).
  void run(const std::atomic<bool>& interrupt);

  /// Requests a Shutdown (as SIGINT does), from the thread that cycles; other threads
  /// use run()'s `interrupt` flag.
  void interrupt();

  /// State at the end of the last cycle. Safe to read from any thread, as are
  /// nb_cycles() and nb_simulation_steps(); the other accessors belong to the thread
  /// that cycles (or to anyone once run() has returned).
  SpineState state() const { return published_state_.load(std::memory_order_acquire); }
  const SharedMemory& memory() const { return memory_; }
  /// The action currently applied (spine.md defaults after a reset).
  const ServoAction& action() const { return action_; }
  /// Message of the exception that shut the spine down, empty if none.
  const std::string& error() const { return error_; }
  /// Cycles run so far, and simulation step() calls so far.
  std::uint64_t nb_cycles() const { return nb_cycles_.load(std::memory_order_relaxed); }
  std::uint64_t nb_simulation_steps() const {
    return nb_simulation_steps_.load(std::memory_order_relaxed);
  }

 private:
  void process_state();
  /// A cycle threw `message`: Shutdown, or Over when the Shutdown itself failed.
  void fail(const std::string& message);
  void reset_from_payload();
  void step_from_payload();
  /// One simulation step with the commands the agent sent, through the actuation.
  void advance_sent();
  /// One simulation step applying `action` as it is; the observer sees `logged`.
  void advance(const ServoAction& action, const ServoAction& logged);
  void write_observation();
  void remember_observation();
  void publish_state() { published_state_.store(machine_.state(), std::memory_order_release); }

  Simulation& simulation_;
  SpineServerConfig config_;
  BrakeStep brake_step_;
  SettingsSetter set_settings_;
  SimulationObserver observer_;
  SharedMemory memory_;
  SpineStateMachine machine_;
  PayloadUnpacker unpacker_;
  Dictionary configuration_;
  Dictionary action_dictionary_;
  ServoAction action_{};
  ServoAction stop_action_{};
  ServoActionLag actuation_;
  msgpack::sbuffer buffer_;
  bool simulation_ready_ = false;
  std::string error_;
  /// The last observation_delay_steps + 1 observations, a ring; history_next_ is the
  /// oldest (the one written to the agent).
  std::vector<Observation> history_;
  std::size_t history_next_ = 0;
  std::atomic<SpineState> published_state_;
  std::atomic<std::uint64_t> nb_cycles_{0};
  std::atomic<std::uint64_t> nb_simulation_steps_{0};
};

}  // namespace upkie_rl
