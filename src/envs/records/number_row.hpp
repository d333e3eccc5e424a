#pragma once
/// @file
/// parse_number_row: a line of comma-separated numbers (the velocity command files of
/// `rollout --commands` and the command lines of `upkie-rl-agent`).

#include <span>
#include <string_view>

namespace upkie_rl {

/// Parses `line` as exactly values.size() comma-separated finite-or-not numbers (spaces,
/// tabs and a carriage return around each allowed) into `values`; false if it is not that.
/// Allocates nothing.
bool parse_number_row(std::string_view line, std::span<double> values);

}  // namespace upkie_rl
