#pragma once
/// @file
/// SupervisedSpine: the spine backend with the supervisor between the task and the spine.

#include <atomic>
#include <memory>

#include "agent/supervisor.hpp"
#include "sim/simulation.hpp"
#include "spine/spine_backend.hpp"

namespace upkie_rl {

/// A Simulation backend for the task chain (ServosEnv and the task above it) that checks
/// and limits what goes to the spine: every servo action is limited by the supervisor
/// before it is sent, every observation checked when it arrives (a SupervisorTrip stops the
/// run). In dry-run mode the task's commands are only kept (intended_action()): the spine
/// gets the stop commands instead, which still bring a fresh observation each cycle (the
/// spine answers requests only).
class SupervisedSpine final : public Simulation {
 public:
  /// @param supervisor Outlives this object.
  SupervisedSpine(std::unique_ptr<SpineBackend> spine, Supervisor& supervisor, bool dry_run);

  /// Stop, then Start with `state` (the spine link's reset); checks the first observation.
  /// @throws SupervisorTrip, SpineError, SpineTimeoutError.
  const Observation& reset(const ResetState& state) override;

  /// Limits `action`, sends it (or, in dry run, the stop commands), checks the reply.
  /// @throws SupervisorTrip, SpineError, SpineTimeoutError.
  const Observation& step(const ServoAction& action) override;

  const Observation& observation() const override { return spine_->observation(); }
  double agent_timestep() const override { return spine_->agent_timestep(); }

  /// The task's last commands after the supervisor's limits (what dry run does not send).
  const ServoAction& intended_action() const { return intended_; }

  /// The stopping state's commands: `nb_stop_cycles` cycles of stop commands, then the Stop
  /// request. Returns how many stop cycles the spine answered; a silent spine gets the Stop
  /// request written anyway (it acts on it if it comes back). `cut_short` set (an operator's
  /// second Ctrl-C) ends the stop cycles early: the Stop request follows at once.
  /// @throws SpineError when even the Stop request cannot be written (an Error reply).
  int send_stop_commands(int nb_stop_cycles, const std::atomic<bool>& cut_short);

 private:
  std::unique_ptr<SpineBackend> spine_;
  Supervisor& supervisor_;
  bool dry_run_;
  ServoAction intended_{};
  ServoAction stop_{};
};

}  // namespace upkie_rl
