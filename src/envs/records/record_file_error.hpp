#pragma once
/// @file
/// The error of a record file that `upkie-rl render` or `upkie-rl view` cannot read.

#include "base/error.hpp"

namespace upkie_rl {

/// Raised on a record file that cannot be read: missing, empty, a missing column, a value
/// that is not a number, a row of the wrong length, no ground truth, no rows. The message
/// names the file and, for a row, its line and column.
class RecordFileError : public Error {
 public:
  using Error::Error;
};

}  // namespace upkie_rl
