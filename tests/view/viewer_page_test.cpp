#include "view/viewer_page.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "view/view_error.hpp"
#include "view/view_frame.hpp"
#include "view/view_session.hpp"

namespace upkie_rl {
namespace {

std::size_t count(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos;
       at = text.find(needle, at + 1)) {
    ++n;
  }
  return n;
}

ViewSession two_frame_replay() {
  ViewSession session;
  session.mode = ViewSession::Mode::kReplay;
  session.title = "a </script><script>alert(1)</script> title";  // must stay text
  session.action_names = {"ground_velocity"};
  session.episodes.push_back({0, std::vector<double>(2 * view_frame_size(1), 0.5)});
  return session;
}

TEST(ViewerPage, TheBundleIsBuiltAndCanBeInlined) {
  const std::string_view script = viewer_script();
  EXPECT_GT(script.size(), 100'000u) << "three.js, urdf-loader and uPlot are bundled";
  // An HTML comment opener inside an inline script could change how the page is parsed.
  EXPECT_EQ(std::string(script).find("<!--"), std::string::npos);
}

TEST(ViewerPage, TheServedPageLoadsTheScriptAndTheSession) {
  const std::string page = served_viewer_page();
  EXPECT_NE(page.find("<script src=\"viewer.js\"></script>"), std::string::npos);
  EXPECT_EQ(page.find("UPKIE_SESSION"), std::string::npos);
  EXPECT_EQ(page.find("upkie-session"), std::string::npos);
}

TEST(ViewerPage, TheSelfContainedPageHoldsScriptAndSessionIntact) {
  const std::string json = view_session_json(two_frame_replay(), UPKIE_RL_MODEL_PATH);
  const std::string page = self_contained_viewer_page(json);
  // Two script elements, each closed once: nothing inside ends them early.
  EXPECT_EQ(count(page, "<script"), 2u);
  EXPECT_EQ(count(page, "</script>"), 2u);
  // Nothing is loaded from elsewhere (the browser test also replays it offline).
  EXPECT_EQ(page.find("<script src"), std::string::npos);
  EXPECT_EQ(page.find("<link rel=\"stylesheet\""), std::string::npos);
  const std::string open = "<script id=\"upkie-session\" type=\"application/json\">";
  const std::size_t begin = page.find(open) + open.size();
  const std::size_t end = page.find("</script>", begin);
  const nlohmann::json session = nlohmann::json::parse(page.substr(begin, end - begin));
  EXPECT_EQ(session, nlohmann::json::parse(json));
  EXPECT_EQ(session["title"], "a </script><script>alert(1)</script> title");
  EXPECT_EQ(session["episodes"][0]["frames"].size(), 2 * view_frame_size(1));
  EXPECT_NE(session["urdf"].get<std::string>().find("<robot name=\"upkie\">"), std::string::npos);
}

TEST(ViewSession, LiveSessionsNameTheirWebSocket) {
  ViewSession session;
  session.action_names = {"a", "b"};
  const nlohmann::json json =
      nlohmann::json::parse(view_session_json(session, UPKIE_RL_MODEL_PATH));
  EXPECT_EQ(json["mode"], "live");
  EXPECT_EQ(json["websocket"], kViewFramesPath);
  EXPECT_EQ(json["frame_fields"].size(), view_frame_size(2));
  EXPECT_FALSE(json.contains("episodes"));
}

TEST(ViewSession, RefusesPartialFramesAndAMissingRobot) {
  ViewSession session = two_frame_replay();
  session.episodes[0].frames.pop_back();
  EXPECT_THROW(view_session_json(session, UPKIE_RL_MODEL_PATH), ViewError);
  try {
    view_session_json(two_frame_replay(), "/nonexistent/upkie.urdf");
    FAIL();
  } catch (const ViewError& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/upkie.urdf"), std::string::npos);
  }
}

}  // namespace
}  // namespace upkie_rl
