#pragma once
/// @file
/// The size limit of a YAML configuration file (a training config, a sweep's files).

#include <cstdint>

namespace upkie_rl {

/// Largest YAML configuration file read: ours are a few KiB, so 4 MiB is room for any
/// hand-written one and refuses a runaway file at once.
inline constexpr std::uintmax_t kMaxConfigFileBytes = std::uintmax_t{4} << 20;

}  // namespace upkie_rl
