#pragma once
/// @file
/// JSON parsing for text that comes from files or peers: nlohmann::json recurses once per
/// nesting level when it builds, compares, prints and destroys values, so a deeply nested
/// document (e.g. 100,000 '[') overflows the stack. The depth is checked on the raw text
/// first, without recursion.

#include <cstddef>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace upkie_rl {

/// Deepest nesting of arrays and objects accepted by parse_bounded_json.
inline constexpr std::size_t kMaxJsonDepth = 64;

/// Deepest nesting of '[' and '{' outside strings in `text` (no validation otherwise).
std::size_t json_nesting_depth(std::string_view text);

/// Parses `text`. Throws std::invalid_argument naming `where` when the text is nested
/// deeper than `max_depth` or is not JSON (one line).
nlohmann::json parse_bounded_json(std::string_view text, const std::string& where,
                                  std::size_t max_depth = kMaxJsonDepth);

}  // namespace upkie_rl
