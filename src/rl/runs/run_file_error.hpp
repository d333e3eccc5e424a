#pragma once
/// @file
/// The error of a training run's or a sweep's files.

#include "base/error.hpp"

namespace upkie_rl {

/// Raised when a run's or a sweep's files cannot be read or written: progress.csv or the
/// TensorBoard events (unreadable, another header, a cut row), the run directory's lock
/// (held by another trainer), a run directory that already holds another run, config.yaml,
/// sweep.yaml, an exported model. The message names the file.
class RunFileError : public Error {
 public:
  using Error::Error;
};

}  // namespace upkie_rl
