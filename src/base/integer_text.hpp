#pragma once
/// @file
/// Reading one integer from text, strictly: the one parser of configuration values and
/// launcher variables, so that they accept the same spellings.

#include <charconv>
#include <optional>
#include <string_view>

#include "base/trim.hpp"

namespace upkie_rl {

/// The integer `text` spells in decimal, spaces, tabs and line ends around it allowed; or
/// nullopt when it is empty, has anything else (a sign "+", a fraction, trailing
/// characters) or does not fit in T. Callers word the error, naming their key.
template <class T>
std::optional<T> integer_from_text(std::string_view text) {
  text = trim(text);
  if (text.empty()) return std::nullopt;
  T value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

}  // namespace upkie_rl
