#pragma once
/// @file
/// Range checks for numeric settings (configuration keys, `--set` overrides, command-line
/// flags, Python arguments), run once before anything is allocated or started. Every check
/// throws std::invalid_argument with one line naming the setting, its value and the limit,
/// so the command line and Python report the same thing.

#include <concepts>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace upkie_rl {

/// Whether a range's lower bound belongs to it: [min, max] or (min, max].
enum class LowerBound { kIncluded, kExcluded };

/// Throws unless `value` is finite and inside [min, max] (or (min, max]).
/// `name` is how the user wrote the setting, e.g. "config key 'ppo.clip_range'".
void check_setting(const std::string& name, double value, double min, double max,
                   LowerBound lower = LowerBound::kIncluded);

/// The same, showing the value as `shown` (as the user wrote it; "" for the shortest text
/// that reads back as `value`).
void check_setting(const std::string& name, double value, const std::string& shown, double min,
                   double max, LowerBound lower = LowerBound::kIncluded);

/// Throws unless min <= value <= max, showing the value as `shown` (as the user wrote it;
/// "" for its decimal text).
template <std::integral Integer>
void check_setting(const std::string& name, Integer value, const std::string& shown, Integer min,
                   Integer max) {
  if (value >= min && value <= max) return;
  throw std::invalid_argument(name + ": " + (shown.empty() ? std::to_string(value) : shown) +
                              " is outside [" + std::to_string(min) + ", " + std::to_string(max) +
                              "]");
}

/// Throws unless min <= value <= max.
inline void check_setting(const std::string& name, std::int64_t value, std::int64_t min,
                          std::int64_t max) {
  check_setting(name, value, "", min, max);
}

/// Bytes of physical memory of this machine (0 when unknown).
std::uint64_t physical_memory_bytes();

/// Throws when `bytes`, what setting `name` = `value` would make `what` allocate, exceed
/// half of this machine's physical memory (the other half is left to the simulators, the
/// optimiser and the rest of the machine). Does nothing when the memory size is unknown.
void check_allocation(const std::string& name, const std::string& value, double bytes,
                      const std::string& what);

}  // namespace upkie_rl
