#pragma once
/// @file
/// The errors of the robot runner (`upkie-rl-agent`).

#include "base/error.hpp"

namespace upkie_rl {

/// Raised when the runner cannot run: a bad option, checkpoint or environment, or a
/// supervisor limit passed (SupervisorTrip).
class AgentError : public Error {
 public:
  using Error::Error;
};

/// Raised inside a cycle when the supervisor finds the robot or the policy outside its
/// limits; the runner then goes to the stopping state. The message names the limit.
class SupervisorTrip : public AgentError {
 public:
  using AgentError::AgentError;
};

}  // namespace upkie_rl
