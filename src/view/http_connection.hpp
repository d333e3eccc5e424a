#pragma once
/// @file
/// HttpConnection: one browser's TCP connection to the viewer server until it becomes a
/// WebSocket. It reads requests (at most kViewMaxRequestBytes, each within the idle
/// timeout), refuses those whose Host header names another site (view/origin_check.hpp),
/// answers page requests from the ViewerRoutes, and hands on a WebSocket handshake whose
/// Origin is the viewer's own. Lives on the server's io thread.

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>

#include "view/viewer_routes.hpp"

namespace upkie_rl {

class HttpConnection : public std::enable_shared_from_this<HttpConnection> {
 public:
  /// What the server does with the connection's requests.
  struct Handlers {
    std::function<void()> on_request;  ///< Any request read whole.
    /// A WebSocket handshake that passed the Host and Origin checks: the handler takes
    /// the socket (release_socket) or refuses it.
    std::function<void(const std::shared_ptr<HttpConnection>&, const HttpRequest&)> on_upgrade;
  };

  struct Settings {
    bool loopback = true;  ///< The server listens on a loopback address (is_allowed_host).
    std::chrono::steady_clock::duration idle_timeout;
  };

  /// Counts itself in `open_connections` while it lives; `routes`, `handlers` and
  /// `open_connections` must outlive it (the io context's destruction ends it).
  HttpConnection(boost::asio::ip::tcp::socket socket, const ViewerRoutes& routes,
                 const Handlers& handlers, const Settings& settings, std::size_t& open_connections);
  ~HttpConnection();
  HttpConnection(const HttpConnection&) = delete;
  HttpConnection& operator=(const HttpConnection&) = delete;

  /// Reads the first request.
  void start() { read_request(); }

  /// Answers `request` with a plain HTTP `status` and `reason`, then closes.
  void refuse(const HttpRequest& request, boost::beast::http::status status, const char* reason);

  /// The socket, for the WebSocket; the connection is done with it.
  boost::asio::ip::tcp::socket release_socket();

 private:
  void read_request();
  void dispatch(const HttpRequest& request);
  void answer(const HttpRequest& request);

  boost::beast::tcp_stream stream_;
  boost::beast::flat_buffer buffer_;
  const ViewerRoutes& routes_;
  const Handlers& handlers_;
  Settings settings_;
  std::size_t& open_connections_;
};

}  // namespace upkie_rl
