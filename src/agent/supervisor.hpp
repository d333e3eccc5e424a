#pragma once
/// @file
/// Supervisor: the robot runner's state machine and limits, between the task (the same
/// code as in training) and the spine.

#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "agent/supervisor_limits.hpp"
#include "agent/supervisor_state.hpp"
#include "envs/spaces/box_space.hpp"
#include "model/robot_model.hpp"
#include "sim/observation.hpp"
#include "sim/servo_command.hpp"

namespace upkie_rl {

/// Holds the runner's state (one log line per change), checks every observation and policy
/// output against the limits, and limits every servo command before it is sent. The checks
/// allocate nothing unless a limit is passed (then they throw SupervisorTrip).
class Supervisor {
 public:
  /// @param timestep The agent's period [s], for the rate limits.
  /// @throws AgentError on invalid limits.
  Supervisor(const SupervisorLimits& limits, std::shared_ptr<const RobotModel> model,
             double timestep);

  SupervisorState state() const { return state_; }
  const SupervisorLimits& limits() const { return limits_; }

  /// Goes to `next` and logs "supervisor: <from> -> <to>: <reason>". A second change to the
  /// same state is ignored (no line).
  void transition(SupervisorState next, std::string_view reason);

  /// @throws SupervisorTrip naming the limit: pitch or roll beyond their bounds, a joint
  ///         angle beyond its limits plus the margin, a joint velocity beyond its bound, or a
  ///         non-finite measurement.
  void check_observation(const Observation& observation) const;

  /// @throws SupervisorTrip when a component is not finite or outside `space`.
  void check_policy_output(std::span<const float> action, const BoxSpace& space) const;

  /// Caps every maximum_torque (limits.max_torque, never above the joint's effort) and
  /// rate-limits every position and velocity command against the last command sent.
  void limit_commands(ServoAction& action);

  /// Starts the rate limits from the measured state (legs at their angles, wheels still).
  void reset_commands(const Observation& observation);

  /// The stop commands: zero wheel velocity, legs held at their angles in `observation`,
  /// torques capped as limit_commands does.
  ServoAction stop_action(const Observation& observation) const;

 private:
  double torque_cap(std::size_t servo) const;

  SupervisorLimits limits_;
  std::shared_ptr<const RobotModel> model_;
  double timestep_;
  SupervisorState state_ = SupervisorState::kIdle;
  ServoAction last_sent_{};
};

}  // namespace upkie_rl
