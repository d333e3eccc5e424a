#pragma once
/// @file
/// Writing a number as text: the one spelling of values that must read back exactly
/// (option values, range messages, TorchScript literals, CSV cells).

#include <charconv>
#include <concepts>
#include <string>

namespace upkie_rl {

/// The shortest text that reads back as `value` ("0.0003", "1e-08", "1e+39", "nan", "-inf").
template <std::floating_point Real>
std::string shortest_text(Real value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

}  // namespace upkie_rl
