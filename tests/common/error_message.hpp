#pragma once
/// @file
/// The message of the error a piece of code throws: what the bad-input tests compare.

#include <stdexcept>
#include <string>
#include <utility>

namespace upkie_rl::testing {

/// The message of the `Error` that `run()` throws, or "" when it throws none (another
/// exception passes through and fails the test).
template <class Error = std::invalid_argument, class Run>
std::string error_message(Run&& run) {
  try {
    std::forward<Run>(run)();
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

}  // namespace upkie_rl::testing
