#pragma once
/// @file
/// The viewer's web page (web/viewer/, bundled by the build with three.js, urdf-loader and
/// uPlot, and compiled into the library), as served or as one self-contained file.

#include <string>
#include <string_view>

namespace upkie_rl {

/// The bundled script, served as /viewer.js.
std::string_view viewer_script();

/// The page the server gives at /: it loads /viewer.js, then /session.json.
std::string served_viewer_page();

/// One HTML file holding the script and the session (view_session_json), which plays with
/// no server and no network.
std::string self_contained_viewer_page(const std::string& session_json);

}  // namespace upkie_rl
