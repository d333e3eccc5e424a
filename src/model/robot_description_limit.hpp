#pragma once
/// @file
/// The size limit of a robot description read from a file (RobotModel, the viewer's page).

#include <cstdint>

namespace upkie_rl {

/// Largest robot description (URDF) read: upkie.urdf is about 10 KiB and meshes are separate
/// files, so 16 MiB is room for any robot and refuses a runaway file at once.
inline constexpr std::uintmax_t kMaxRobotDescriptionBytes = std::uintmax_t{16} << 20;

}  // namespace upkie_rl
