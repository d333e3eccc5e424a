#pragma once
/// @file
/// A WebSocket client of the viewer's frame stream (ViewServer's /frames), for tests.

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

namespace upkie_rl::testing {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace websocket = beast::websocket;
using tcp = net::ip::tcp;

/// A WebSocket client of /frames with reads that give up after a timeout.
class FrameClient {
 public:
  /// Connects to 127.0.0.1:`port`; `origin`, when given, is sent as a browser would.
  explicit FrameClient(int port, int receive_buffer = 0, const std::string& origin = {})
      : ws_(io_) {
    tcp::socket& socket = beast::get_lowest_layer(ws_).socket();
    socket.open(tcp::v4());
    if (receive_buffer > 0)
      socket.set_option(net::socket_base::receive_buffer_size(receive_buffer));
    socket.connect(
        tcp::endpoint(net::ip::make_address("127.0.0.1"), static_cast<unsigned short>(port)));
    if (!origin.empty()) {
      ws_.set_option(websocket::stream_base::decorator([origin](websocket::request_type& request) {
        request.set(beast::http::field::origin, origin);
      }));
    }
    // The Host header a browser sends: address and port.
    ws_.handshake("127.0.0.1:" + std::to_string(port), "/frames");
  }

  /// The next message, or nothing after `timeout`.
  std::optional<std::string> read(
      std::chrono::milliseconds timeout = std::chrono::milliseconds(5000)) {
    buffer_.clear();
    bool done = false;
    beast::error_code error;
    ws_.async_read(buffer_, [&](beast::error_code e, std::size_t) {
      error = e;
      done = true;
    });
    io_.restart();
    io_.run_for(timeout);
    if (!done) {
      beast::get_lowest_layer(ws_).cancel();
      io_.restart();
      io_.run();
      return std::nullopt;
    }
    if (error) return std::nullopt;
    binary_ = ws_.got_binary();
    return beast::buffers_to_string(buffer_.data());
  }

  /// Reads until `count` frames of `frame_size` values have come (or a read times out);
  /// returns them.
  std::vector<double> read_frames(std::size_t frame_size, std::size_t count) {
    std::vector<double> frames;
    while (frames.size() < count * frame_size) {
      const std::optional<std::string> message = read();
      if (!message) break;
      if (!binary_) continue;
      const std::size_t old = frames.size();
      frames.resize(old + message->size() / sizeof(double));
      std::memcpy(frames.data() + old, message->data(), message->size());
    }
    return frames;
  }

  bool binary() const { return binary_; }
  void close_abruptly() { beast::get_lowest_layer(ws_).socket().close(); }

 private:
  net::io_context io_;
  websocket::stream<beast::tcp_stream> ws_;
  beast::flat_buffer buffer_;
  bool binary_ = false;
};

}  // namespace upkie_rl::testing
