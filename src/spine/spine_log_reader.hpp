#pragma once
/// @file
/// Reading a spine log (spine/spine_log.hpp): Upkie's spines, `upkie-rl spine --log`, or any
/// writer of the `mpacklog` format with the spine's keys.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "spine/spine_log.hpp"

namespace upkie_rl {

/// The cycles of the spine log at `path`, at most kMaxSpineLogBytes. Dictionaries without an
/// observation (none in a spine's log) are skipped; the action dictionary is merged from
/// cycle to cycle as the spine merges it, starting from the spine's default action.
/// @throws RobotLogError, one line naming the file, the dictionary and the problem: a
///         truncated or malformed stream, an entry that is not a dictionary, a missing key
///         (servo positions, velocities and torques, base pitch and angular velocity, wheel
///         odometry), a non-finite measurement or one beyond kMaxLoggedMagnitude (1e308), a
///         command that is not a number, time that does not increase, fewer than 2 cycles.
std::vector<LoggedCycle> read_spine_log(const std::filesystem::path& path);

/// The same, from the bytes of a log; `name` stands for the file in messages.
std::vector<LoggedCycle> read_spine_log(std::string_view bytes, const std::string& name);

/// Whether `bytes` start like a spine log (a MessagePack map) rather than a CSV header.
bool looks_like_spine_log(std::string_view bytes);

/// @throws RobotLogError naming `what` (a key or a column) and `where` when `value` is NaN,
///         infinite or beyond kMaxLoggedMagnitude.
void check_logged_value(double value, std::string_view what, const std::string& where);

}  // namespace upkie_rl
