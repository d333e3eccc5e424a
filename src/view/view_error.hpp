#pragma once
/// @file
/// The error of the view layer.

#include "base/error.hpp"

namespace upkie_rl {

/// Raised when the viewer cannot start or its input is unusable: a busy or forbidden port,
/// an address that is not an IPv4/IPv6 literal, a viewer page that was not built, a frame
/// of the wrong size. The message names the cause.
class ViewError : public Error {
 public:
  using Error::Error;
};

}  // namespace upkie_rl
