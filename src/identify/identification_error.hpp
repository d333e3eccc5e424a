#pragma once
/// @file
/// The error of an identification that cannot be carried out.

#include "base/error.hpp"

namespace upkie_rl {

/// Raised when the fit itself fails (the optimiser stops with an error status); bad logs
/// raise RobotLogError and bad options std::invalid_argument before the fit starts.
class IdentificationError : public Error {
 public:
  using Error::Error;
};

}  // namespace upkie_rl
