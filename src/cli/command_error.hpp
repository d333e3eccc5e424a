#pragma once
/// @file
/// The error of a command of `upkie-rl` that cannot do what it was asked.

#include "base/error.hpp"

namespace upkie_rl::apps {

/// Raised by a command when its options ask for what it cannot do (`--video` of an
/// environment without a simulation, a TorchScript file without upkie-rl's metadata), when a
/// tool it runs fails (gnuplot, a child process) or when it is interrupted. main() prints it
/// as one line `upkie-rl: error: ...` and exits with status 1.
class CommandError : public Error {
 public:
  using Error::Error;
};

}  // namespace upkie_rl::apps
