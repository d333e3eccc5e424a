#include "view/view_client.hpp"

#include <boost/asio/buffer.hpp>

#include "view/view_server.hpp"

namespace upkie_rl {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace websocket = beast::websocket;
using tcp = net::ip::tcp;

namespace {

/// Text messages waiting for one browser beyond this are dropped (a page that floods the
/// server with refused messages must not grow its queue without bound).
constexpr std::size_t kMaxQueuedTexts = 64;

}  // namespace

ViewClient::ViewClient(tcp::socket socket, ViewClientHost& host, const FrameBroadcaster& frames,
                       std::size_t max_frames_per_message)
    : stream_(std::move(socket)),
      host_(host),
      frames_(frames),
      max_frames_per_message_(max_frames_per_message) {
  // Small messages (a driving acknowledgement) go out at once: with Nagle's algorithm one
  // written right after another waits for the browser's delayed ACK (40 ms on Linux).
  beast::error_code ignored;
  beast::get_lowest_layer(stream_).socket().set_option(tcp::no_delay(true), ignored);
  stream_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
  stream_.read_message_max(kViewMaxRequestBytes);
  stream_.binary(true);
  const std::uint64_t newest = frames_.newest();
  last_frame_ = newest > frames_.capacity() ? newest - frames_.capacity() : 0;
}

void ViewClient::open(const HttpRequest& request) {
  // Kept alive until the handshake is over.
  auto held = std::make_shared<HttpRequest>(request);
  stream_.async_accept(*held, [self = shared_from_this(), held](beast::error_code error) {
    if (error) return;
    self->transition(ClientEvent::kAccepted);
    self->host_.opened(self);
    self->read_messages();
    self->send();
  });
}

void ViewClient::read_messages() {
  stream_.async_read(incoming_, [self = shared_from_this()](beast::error_code error, std::size_t) {
    if (error) {
      self->drop();
      return;
    }
    if (!self->stream_.got_binary()) {
      const auto data = self->incoming_.cdata();
      self->host_.received(*self,
                           std::string_view(static_cast<const char*>(data.data()), data.size()));
    }
    self->incoming_.clear();  // a page that does not drive sends nothing the server needs
    self->read_messages();
  });
}

void ViewClient::queue_text(std::string text) {
  if (!is_open(state_) || texts_.size() >= kMaxQueuedTexts) return;
  texts_.push_back(std::move(text));
  send();
}

void ViewClient::pace(Clock::time_point now, std::chrono::duration<double> write_timeout) {
  if (!is_writing(state_)) {
    send();
  } else if (now - write_started_ > write_timeout) {
    drop();
  }
}

void ViewClient::drop() {
  if (!is_open(state_)) return;
  transition(ClientEvent::kDropped);
  beast::error_code ignored;
  beast::get_lowest_layer(stream_).socket().close(ignored);
  host_.dropped(shared_from_this());
}

template <typename Buffer, typename Handler>
void ViewClient::start_write(ClientEvent event, const Buffer& buffer, bool binary,
                             Handler&& on_written) {
  transition(event);
  stream_.binary(binary);
  write_started_ = Clock::now();
  stream_.async_write(buffer, std::forward<Handler>(on_written));
}

void ViewClient::send() {
  if (state_ != ClientState::kIdle) return;
  if (texts_.empty()) {
    send_frames();
    return;
  }
  text_ = std::move(texts_.front());
  texts_.pop_front();
  start_write(ClientEvent::kTextStarted, net::buffer(text_), false,
              [self = shared_from_this()](beast::error_code error, std::size_t) {
                if (error) {
                  self->drop();
                  return;
                }
                self->transition(ClientEvent::kWritten);
                self->send();  // the next text, or frames
              });
}

void ViewClient::send_frames() {
  outgoing_.clear();
  const FrameBroadcaster::Collected collected =
      frames_.collect(last_frame_, max_frames_per_message_, outgoing_);
  last_frame_ = collected.newest;
  const std::size_t count = outgoing_.size() / frames_.frame_size();
  host_.frames_collected(count, collected.skipped);
  const auto on_written = [self = shared_from_this()](beast::error_code error, std::size_t) {
    if (error) {
      self->drop();
      return;
    }
    self->transition(ClientEvent::kWritten);
    if (self->state_ == ClientState::kClosing) self->close();  // the end message went out
  };
  if (count > 0) {
    start_write(ClientEvent::kFramesStarted,
                net::buffer(outgoing_.data(), outgoing_.size() * sizeof(double)), true, on_written);
  } else if (const std::string* end = host_.end_message()) {
    text_ = *end;
    start_write(ClientEvent::kEndStarted, net::buffer(text_), false, on_written);
  }
}

void ViewClient::close() {
  write_started_ = Clock::now();  // kClosing: nothing more is sent
  stream_.async_close(websocket::close_code::normal,
                      [self = shared_from_this()](beast::error_code) { self->drop(); });
}

}  // namespace upkie_rl
