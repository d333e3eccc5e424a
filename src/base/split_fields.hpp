#pragma once
/// @file
/// Splitting a line of separated values ("a,b,,c"): the one splitter of CSV rows, comma
/// lists and grid axes, so that every reader keeps empty fields the same way.

#include <string>
#include <string_view>
#include <vector>

namespace upkie_rl {

/// The fields of `line` between `separator`s, empty ones included: "a,,b" gives {"a", "",
/// "b"}, "a," gives {"a", ""}, "" gives {""}. No quoting: our files write none, and a field
/// holding the separator is split (the readers then report a wrong field count).
std::vector<std::string> split_fields(std::string_view line, char separator = ',');

}  // namespace upkie_rl
