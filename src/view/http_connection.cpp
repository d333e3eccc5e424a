#include "view/http_connection.hpp"

#include <boost/beast/websocket.hpp>

#include "view/origin_check.hpp"
#include "view/view_server.hpp"

namespace upkie_rl {

namespace beast = boost::beast;
namespace http = beast::http;
using tcp = boost::asio::ip::tcp;

HttpConnection::HttpConnection(tcp::socket socket, const ViewerRoutes& routes,
                               const Handlers& handlers, const Settings& settings,
                               std::size_t& open_connections)
    : stream_(std::move(socket)),
      routes_(routes),
      handlers_(handlers),
      settings_(settings),
      open_connections_(open_connections) {
  ++open_connections_;
}

HttpConnection::~HttpConnection() { --open_connections_; }

void HttpConnection::read_request() {
  auto parser = std::make_shared<http::request_parser<http::string_body>>();
  parser->header_limit(kViewMaxRequestBytes);
  parser->body_limit(kViewMaxRequestBytes);
  stream_.expires_after(settings_.idle_timeout);
  http::async_read(stream_, buffer_, *parser,
                   [self = shared_from_this(), parser](beast::error_code error, std::size_t) {
                     if (error) return;  // closed, timed out or malformed: drop the connection
                     self->handlers_.on_request();
                     self->dispatch(parser->release());
                   });
}

void HttpConnection::dispatch(const HttpRequest& request) {
  if (!is_allowed_host(header_value(request, http::field::host), settings_.loopback)) {
    refuse(request, http::status::forbidden,
           "the Host header names another site; this viewer "
           "listens on a loopback address (127.0.0.1, localhost)\n");
  } else if (!beast::websocket::is_upgrade(request)) {
    answer(request);
  } else if (!is_same_origin(header_value(request, http::field::origin),
                             header_value(request, http::field::host))) {
    refuse(request, http::status::forbidden,
           "a page of another site may not open the viewer's WebSocket\n");
  } else {
    handlers_.on_upgrade(shared_from_this(), request);
  }
}

void HttpConnection::answer(const HttpRequest& request) {
  auto response = std::make_shared<HttpResponse>(routes_.respond(request));
  stream_.expires_after(settings_.idle_timeout);
  http::async_write(stream_, *response,
                    [self = shared_from_this(), response](beast::error_code error, std::size_t) {
                      if (error || !response->keep_alive()) {
                        beast::error_code ignored;
                        self->stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
                        return;
                      }
                      self->read_request();
                    });
}

void HttpConnection::refuse(const HttpRequest& request, http::status status, const char* reason) {
  auto response = std::make_shared<HttpResponse>(status, request.version());
  response->set(http::field::content_type, "text/plain");
  response->body() = reason;
  response->prepare_payload();
  http::async_write(stream_, *response,
                    [self = shared_from_this(), response](beast::error_code, std::size_t) {
                      beast::error_code ignored;
                      self->stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
                    });
}

tcp::socket HttpConnection::release_socket() {
  stream_.expires_never();  // the websocket stream keeps its own timeouts
  return stream_.release_socket();
}

}  // namespace upkie_rl
