#pragma once
/// @file
/// The error of ONNX export and reading.

#include <stdexcept>

namespace upkie_rl {

/// Raised for a model that cannot be exported, or an ONNX file that cannot be written or
/// read (missing, too large, not ONNX, invalid); the message names the file and the problem.
class OnnxError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace upkie_rl
