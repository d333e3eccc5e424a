#pragma once
/// @file
/// The viewer's built files, compiled in by CMake (cmake/embed_viewer.cmake writes
/// viewer_assets.cpp from web/viewer's build), so that the binary needs no file at run time.

#include <string_view>

namespace upkie_rl {

/// web/viewer/src/index.html, with its <!--UPKIE_SESSION--> and <!--UPKIE_SCRIPT--> slots.
std::string_view viewer_page_template();

/// The page's script: web/viewer/src bundled with its npm dependencies (viewer.js).
std::string_view viewer_bundle();

}  // namespace upkie_rl
