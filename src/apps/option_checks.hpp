#pragma once
/// @file
/// Checks of command-line option values that CLI11's own validators miss.

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdlib>
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

}  // namespace upkie_rl::apps
