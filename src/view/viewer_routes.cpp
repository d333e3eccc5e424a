#include "view/viewer_routes.hpp"

#include <algorithm>

#include "view/viewer_page.hpp"

namespace upkie_rl {

namespace http = boost::beast::http;

std::string_view request_path(const HttpRequest& request) {
  const std::string_view target(request.target().data(), request.target().size());
  return target.substr(0, target.find('?'));
}

std::string_view header_value(const HttpRequest& request, http::field field) {
  const auto found = request.find(field);
  return found == request.end() ? std::string_view()
                                : std::string_view(found->value().data(), found->value().size());
}

ViewerRoutes::ViewerRoutes(std::string session_json)
    : page_(served_viewer_page()),
      session_json_(std::move(session_json)),
      routes_{{{"/", "text/html; charset=utf-8", page_},
               {"/index.html", "text/html; charset=utf-8", page_},
               {"/viewer.js", "text/javascript; charset=utf-8", viewer_script()},
               {"/session.json", "application/json", session_json_}}} {}

HttpResponse ViewerRoutes::respond(const HttpRequest& request) const {
  HttpResponse response;
  response.version(request.version());
  response.keep_alive(request.keep_alive());
  response.set(http::field::server, "upkie-rl");
  response.set(http::field::cache_control, "no-store");
  const std::string_view path = request_path(request);
  const auto route = std::find_if(routes_.begin(), routes_.end(), [path](const Route& candidate) {
    return candidate.path == path;
  });
  if (request.method() != http::verb::get && request.method() != http::verb::head) {
    response.result(http::status::method_not_allowed);
    response.set(http::field::content_type, "text/plain");
    response.body() = "only GET and HEAD\n";
  } else if (route != routes_.end()) {
    response.set(http::field::content_type, route->content_type);
    response.body() = std::string(route->body);
  } else {
    response.result(http::status::not_found);
    response.set(http::field::content_type, "text/plain");
    response.body() = "not found\n";
  }
  response.prepare_payload();
  if (request.method() == http::verb::head) response.body().clear();
  return response;
}

}  // namespace upkie_rl
