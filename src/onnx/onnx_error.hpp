#pragma once
/// @file
/// The error of ONNX export and reading.

#include "base/error.hpp"

namespace upkie_rl {

/// Raised for a model that cannot be exported, or an ONNX file that cannot be written or
/// read (missing, too large, not ONNX, invalid); the message names the file and the problem.
class OnnxError : public Error {
 public:
  using Error::Error;
};

}  // namespace upkie_rl
