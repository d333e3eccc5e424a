#pragma once
/// @file
/// The error of the render layer.

#include "base/error.hpp"

namespace upkie_rl {

/// Raised when a frame or a video cannot be made: no OpenGL context, a bad output path, an
/// unsupported extension, FFmpeg missing or failing. The message names the cause.
class RenderError : public Error {
 public:
  using Error::Error;
};

}  // namespace upkie_rl
