#pragma once
/// @file
/// The version and git commit upkie-rl was built from, recorded in the provenance of every
/// model. Defined by a file that cmake/build_info.cmake generates at every build.

namespace upkie_rl {

/// The project version of CMakeLists.txt, e.g. "0.1.0".
const char* upkie_rl_version();

/// The git commit of the source tree at build time (40 hex digits, "-dirty" appended when
/// tracked files had changes), or "unknown" when built outside a git checkout.
const char* upkie_rl_git_commit();

}  // namespace upkie_rl
