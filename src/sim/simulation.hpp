#pragma once
/// @file
/// The interface every backend implements: Bullet, mock, and the spine link.

#include <stdexcept>
#include <string>

#include "base/error.hpp"
#include "sim/observation.hpp"
#include "sim/reset_state.hpp"
#include "sim/servo_command.hpp"

namespace upkie_rl {

/// Raised when the simulated state stops being finite; the simulation must be reset.
class SimulationDivergedError : public Error {
 public:
  using Error::Error;
};

/// A backend that moves the robot: it resets to a state, applies servo commands for one
/// agent step and reports what it observes. Implementations own their world; they are
/// not thread-safe, but different instances may run on different threads.
class Simulation {
 public:
  virtual ~Simulation() = default;

  /// Puts the robot in `state` and returns the first observation.
  virtual const Observation& reset(const ResetState& state) = 0;

  /// Holds `action` for one agent step and returns the observation after it.
  /// @throws InvalidCommandError on a non-finite velocity, torque or gain command.
  /// @throws SimulationDivergedError when the state becomes non-finite.
  virtual const Observation& step(const ServoAction& action) = 0;

  /// The last observation.
  virtual const Observation& observation() const = 0;

  /// Duration of one agent step [s].
  virtual double agent_timestep() const = 0;
};

}  // namespace upkie_rl
