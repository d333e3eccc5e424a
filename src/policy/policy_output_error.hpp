#pragma once
/// @file
/// The error of a loaded policy that cannot give a finite action.

#include "base/error.hpp"

namespace upkie_rl {

/// Raised by DeployedPolicy::act when the network's output is not finite (NaN or infinite)
/// for the observation given, instead of passing it on to an environment or a robot. The
/// checkpoint gate proves the output finite for every observation inside the range it
/// checks (policy/network_output_bound.hpp), so this needs an observation outside it.
class PolicyOutputError : public Error {
 public:
  using Error::Error;
};

}  // namespace upkie_rl
