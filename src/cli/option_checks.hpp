#pragma once
/// @file
/// Checks of command-line option values that CLI11's own validators miss.

#include <CLI/CLI.hpp>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>

namespace upkie_rl::apps {

/// A number option's check: finite and within [min, max]. CLI::Range lets "nan" through
/// (every comparison with NaN is false).
inline CLI::Validator finite_range(double min, double max) {
  const std::string range =
      "[" + CLI::detail::to_string(min) + ", " + CLI::detail::to_string(max) + "]";
  return CLI::Validator(
      [min, max, range](std::string& text) {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !std::isfinite(value) || value < min || value > max) {
          return text + " is not a finite number in " + range;
        }
        return std::string();
      },
      "NUMBER in " + range);
}

/// Refuses an empty value of a path option (`--record ""` would otherwise run and write
/// nothing).
inline const CLI::Validator kNonEmptyPath(
    [](std::string& value) { return value.empty() ? std::string("empty path") : std::string(); },
    "PATH");

/// A seed option's check: decimal digits naming a number in [0, 2^64 - 1], the range of the
/// configuration's `seed`. CLI11 alone turns "-1" and 2^64 into 2^64 - 1 without a word.
inline const CLI::Validator kSeed(
    [](std::string& text) {
      std::string refusal = text + " is not a whole number in [0, " +
                            std::to_string(std::numeric_limits<std::uint64_t>::max()) + "]";
      if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
        return refusal;
      }
      errno = 0;
      static_cast<void>(std::strtoull(text.c_str(), nullptr, 10));
      return errno == ERANGE ? refusal : std::string();
    },
    "SEED in [0, 2^64 - 1]");

/// A frame size option's parse: WIDTHxHEIGHT, two whole numbers and nothing else
/// ("640x480x3" is refused, not read as 640x480). Returns false when `text` is not one.
inline bool parse_frame_size(const std::string& text, int& width, int& height) {
  const std::size_t x = text.find('x');
  if (x == std::string::npos || x == 0 || x + 1 == text.size() ||
      text.find_first_not_of("0123456789x") != std::string::npos ||
      text.find('x', x + 1) != std::string::npos || x > 9 || text.size() - x - 1 > 9) {
    return false;
  }
  width = std::stoi(text.substr(0, x));
  height = std::stoi(text.substr(x + 1));
  return true;
}

}  // namespace upkie_rl::apps
