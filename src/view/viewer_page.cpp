#include "view/viewer_page.hpp"

#include "view/view_error.hpp"
#include "view/viewer_assets.hpp"

namespace upkie_rl {

namespace {

constexpr std::string_view kSessionPlaceholder = "<!--UPKIE_SESSION-->";
constexpr std::string_view kScriptPlaceholder = "<!--UPKIE_SCRIPT-->";

/// Copy of a JavaScript text where every "</" becomes "<\/", so that no "</script" inside
/// it ends its script element; JavaScript reads "\/" as "/" in strings, templates and
/// regular expressions. (The bundle holds no "<!--": a test checks.)
std::string escape_script(std::string_view script) {
  std::string escaped;
  escaped.reserve(script.size() + 64);
  for (std::size_t i = 0; i < script.size(); ++i) {
    escaped.push_back(script[i]);
    if (script[i] == '<' && i + 1 < script.size() && script[i + 1] == '/') escaped.push_back('\\');
  }
  return escaped;
}

/// Copy of a JSON text where every "<" is written "\u003c" (it only occurs in strings), so
/// that neither "</script" nor "<!--" appears in the script element that holds it.
std::string escape_json(std::string_view json) {
  std::string escaped;
  escaped.reserve(json.size() + 1024);
  for (char character : json) {
    if (character == '<') {
      escaped += "\\u003c";
    } else {
      escaped.push_back(character);
    }
  }
  return escaped;
}

std::string fill_template(std::string_view session, std::string_view script) {
  std::string page(viewer_page_template());
  const std::size_t session_at = page.find(kSessionPlaceholder);
  if (session_at == std::string::npos) throw ViewError("the viewer page has no session slot");
  page.replace(session_at, kSessionPlaceholder.size(), session);
  const std::size_t script_at = page.find(kScriptPlaceholder);
  if (script_at == std::string::npos) throw ViewError("the viewer page has no script slot");
  page.replace(script_at, kScriptPlaceholder.size(), script);
  return page;
}

}  // namespace

std::string_view viewer_script() { return viewer_bundle(); }

std::string served_viewer_page() {
  return fill_template("", "<script src=\"viewer.js\"></script>");
}

std::string self_contained_viewer_page(const std::string& session_json) {
  return fill_template(R"(<script id="upkie-session" type="application/json">)" +
                           escape_json(session_json) + "</script>",
                       "<script>" + escape_script(viewer_bundle()) + "</script>");
}

}  // namespace upkie_rl
