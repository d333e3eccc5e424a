#pragma once
/// @file
/// Errors of the spine link.

#include "base/error.hpp"

namespace upkie_rl {

/// A spine link failure: no spine, an invalid request, a malformed or mistyped message.
class SpineError : public Error {
 public:
  using Error::Error;
};

/// The spine did not process a request in time (it is stopped, busy or gone).
class SpineTimeoutError : public SpineError {
 public:
  using SpineError::SpineError;
};

}  // namespace upkie_rl
