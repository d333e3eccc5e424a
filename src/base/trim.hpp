#pragma once
/// @file
/// Removing the spaces, tabs and line ends around a value: the one definition for every
/// reader of configuration text (options, integers, overrides).

#include <string>
#include <string_view>

namespace upkie_rl {

/// The characters trim() removes.
inline constexpr std::string_view kTrimmedSpace = " \t\r\n";

/// `text` without the spaces, tabs and line ends around it ("" when it holds nothing else).
inline std::string_view trim(std::string_view text) {
  const std::size_t begin = text.find_first_not_of(kTrimmedSpace);
  if (begin == std::string_view::npos) return {};
  return text.substr(begin, text.find_last_not_of(kTrimmedSpace) - begin + 1);
}

}  // namespace upkie_rl
