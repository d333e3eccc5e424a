#pragma once
/// @file
/// Numbers as text, both directions: the one spelling of values that must read back exactly
/// (option values, range messages, TorchScript literals, CSV cells) and the one strict reader
/// of numbers in configuration text, record files and command lines.

#include <charconv>
#include <concepts>
#include <optional>
#include <string>
#include <string_view>

#include "base/trim.hpp"

namespace upkie_rl {

/// The shortest text that reads back as `value` ("0.0003", "1e-08", "1e+39", "nan", "-inf").
template <std::floating_point Real>
std::string shortest_text(Real value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

/// The number `text` spells ("0.5", "-1e-3", "nan", "inf"), spaces, tabs and line ends
/// around it allowed; or nullopt when it is empty, has anything else (a sign "+", trailing
/// characters) or is out of Real's range. Non-finite spellings are returned as such: callers
/// that need a finite value check it, and word the error naming their key.
template <std::floating_point Real>
std::optional<Real> number_from_text(std::string_view text) {
  text = trim(text);
  if (text.empty()) return std::nullopt;
  Real value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

}  // namespace upkie_rl
