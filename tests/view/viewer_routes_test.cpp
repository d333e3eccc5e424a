#include "view/viewer_routes.hpp"

#include <gtest/gtest.h>

#include "view/viewer_page.hpp"

namespace upkie_rl {
namespace {

namespace http = boost::beast::http;

HttpRequest request(http::verb method, const std::string& target) {
  HttpRequest request(method, target, 11);
  request.keep_alive(true);
  return request;
}

TEST(ViewerRoutes, EachPathServesItsDocumentWithItsType) {
  const ViewerRoutes routes(R"({"mode":"live"})");
  const HttpResponse page = routes.respond(request(http::verb::get, "/index.html"));
  EXPECT_EQ(page.result(), http::status::ok);
  EXPECT_EQ(page.body(), served_viewer_page());
  EXPECT_EQ(page[http::field::content_type], "text/html; charset=utf-8");
  EXPECT_EQ(page[http::field::cache_control], "no-store");
  EXPECT_TRUE(page.keep_alive());
  const HttpResponse script = routes.respond(request(http::verb::get, "/viewer.js?v=2"));
  EXPECT_EQ(script.body(), viewer_script());
  EXPECT_EQ(script[http::field::content_type], "text/javascript; charset=utf-8");
  const HttpResponse session = routes.respond(request(http::verb::get, "/session.json"));
  EXPECT_EQ(session.body(), R"({"mode":"live"})");
  EXPECT_EQ(session[http::field::content_type], "application/json");
}

TEST(ViewerRoutes, HeadHasTheLengthButNoBody) {
  const ViewerRoutes routes("{}");
  const HttpResponse head = routes.respond(request(http::verb::head, "/session.json"));
  EXPECT_EQ(head.result(), http::status::ok);
  EXPECT_TRUE(head.body().empty());
  EXPECT_EQ(head[http::field::content_length], "2");
}

TEST(ViewerRoutes, RefusesOtherPathsAndMethods) {
  const ViewerRoutes routes("{}");
  EXPECT_EQ(routes.respond(request(http::verb::get, "/frames.json")).result(),
            http::status::not_found);
  EXPECT_EQ(routes.respond(request(http::verb::get, "/session.json/")).result(),
            http::status::not_found);
  const HttpResponse post = routes.respond(request(http::verb::post, "/"));
  EXPECT_EQ(post.result(), http::status::method_not_allowed);
  EXPECT_EQ(post.body(), "only GET and HEAD\n");
}

TEST(ViewerRoutes, RequestPathDropsTheQuery) {
  EXPECT_EQ(request_path(request(http::verb::get, "/frames?token=1")), "/frames");
  EXPECT_EQ(request_path(request(http::verb::get, "/")), "/");
}

}  // namespace
}  // namespace upkie_rl
