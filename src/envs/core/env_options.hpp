#pragma once
/// @file
/// Environment options as the user gives them: key=value strings.

#include <string>
#include <vector>

#include "base/option_table.hpp"

namespace upkie_rl {

/// key=value options, in the order given.
using EnvOptions = OptionValues;

/// Parses "k=v" strings; throws std::invalid_argument naming a malformed one.
EnvOptions parse_env_options(const std::vector<std::string>& key_values);

/// "k1=v1 k2=v2", for messages.
std::string format_env_options(const EnvOptions& options);

}  // namespace upkie_rl
