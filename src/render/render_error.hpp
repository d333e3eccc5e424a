#pragma once
/// @file
/// The error of the render layer.

#include <stdexcept>

namespace upkie_rl {

/// Raised when a frame or a video cannot be made: no OpenGL context, a bad output path, an
/// unsupported extension, FFmpeg missing or failing. The message names the cause.
class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace upkie_rl
