#pragma once
/// @file
/// "Did you mean" for a mistyped name: the one suggestion helper of every refusal that lists
/// valid names (commands of `upkie-rl`, environment ids, configuration keys, environment
/// options), so that they all suggest alike.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace upkie_rl {

/// Edits (insertions, deletions, substitutions, and swaps of two neighbouring characters)
/// that turn `a` into `b`, ignoring ASCII case: "trian" is one from "train",
/// "Upkie-Mujoco-Pendulum" none from "Upkie-MuJoCo-Pendulum".
std::size_t edit_distance(std::string_view a, std::string_view b);

/// The name of `names` nearest to `wrong` (the first of equals), when near enough to be
/// what was meant: at most max(2, size of `wrong` / 4) edits, and fewer than `wrong` has
/// characters. nullopt when none is.
std::optional<std::string> closest_name(std::string_view wrong,
                                        const std::vector<std::string>& names);

/// " (did you mean \"<closest name>\"?)", or "" when no name is near: for a refusal to
/// append after the wrong name.
std::string did_you_mean(std::string_view wrong, const std::vector<std::string>& names);

}  // namespace upkie_rl
