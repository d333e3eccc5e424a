#pragma once
/// @file
/// ViewerRoutes: the viewer server's route table, which document each HTTP path serves
/// (the page, its script, the session document).

#include <array>
#include <boost/beast/http.hpp>
#include <string>
#include <string_view>

namespace upkie_rl {

using HttpRequest = boost::beast::http::request<boost::beast::http::string_body>;
using HttpResponse = boost::beast::http::response<boost::beast::http::string_body>;

/// The path of `request`'s target, without its query.
std::string_view request_path(const HttpRequest& request);

/// The value of header `field` of `request`, empty when it has none.
std::string_view header_value(const HttpRequest& request, boost::beast::http::field field);

class ViewerRoutes {
 public:
  /// @param session_json The session document (view_session_json), served as /session.json.
  explicit ViewerRoutes(std::string session_json);
  ViewerRoutes(const ViewerRoutes&) = delete;  // the table points into the documents
  ViewerRoutes& operator=(const ViewerRoutes&) = delete;

  /// The answer to a page request: GET (or HEAD, without the body) of /, /index.html,
  /// /viewer.js or /session.json; 404 for another path, 405 for another method. Never
  /// cached by the browser (the session changes from one run to the next).
  HttpResponse respond(const HttpRequest& request) const;

 private:
  struct Route {
    std::string_view path;
    const char* content_type;
    std::string_view body;
  };

  std::string page_;
  std::string session_json_;
  std::array<Route, 4> routes_;
};

}  // namespace upkie_rl
