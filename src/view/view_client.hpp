#pragma once
/// @file
/// ViewClient: one browser's WebSocket session on the viewer server. It goes through the
/// states of view/client_state.hpp, one write at a time: queued text messages (driving
/// replies) first, then the frames published since its last message, then, once the run is
/// over and every frame has gone, the end message and the close. A read loop notices when
/// the browser goes away and passes on the page's text messages. Lives on the server's io
/// thread.

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "view/client_state.hpp"
#include "view/frame_broadcaster.hpp"
#include "view/viewer_routes.hpp"

namespace upkie_rl {

class ViewClient;

/// What a ViewClient tells the server, and asks of it.
class ViewClientHost {
 public:
  virtual ~ViewClientHost() = default;
  /// The handshake succeeded: `client` is open.
  virtual void opened(const std::shared_ptr<ViewClient>& client) = 0;
  /// The page sent text message `text`.
  virtual void received(ViewClient& client, std::string_view text) = 0;
  /// `client` is closed (the browser went away, a write failed or timed out, or the close
  /// after the end message is over).
  virtual void dropped(const std::shared_ptr<ViewClient>& client) = 0;
  /// A client collected `frames` frames to send (none: no message) and missed `skipped`.
  virtual void frames_collected(std::size_t frames, std::uint64_t skipped) = 0;
  /// The end message once the run is over, or null.
  virtual const std::string* end_message() const = 0;
};

class ViewClient : public std::enable_shared_from_this<ViewClient> {
 public:
  using Clock = std::chrono::steady_clock;

  /// @param frames Its frames; the client starts with what the ring still holds, so that
  ///        the page's plots fill at once.
  /// @param max_frames_per_message The newest frames of a message beyond this are skipped.
  ViewClient(boost::asio::ip::tcp::socket socket, ViewClientHost& host,
             const FrameBroadcaster& frames, std::size_t max_frames_per_message);

  /// Answers the WebSocket handshake `request`; on success the client is open
  /// (ViewClientHost::opened), reads and sends.
  void open(const HttpRequest& request);

  /// The server's number of the client (for the DriveControl), given when it opens.
  std::uint64_t id() const { return id_; }
  void set_id(std::uint64_t id) { id_ = id; }
  ClientState state() const { return state_; }

  /// Queues a text message and sends it as soon as the writes allow; dropped when the
  /// client is not open or kMaxQueuedTexts wait already.
  void queue_text(std::string text);
  /// The pacer's tick: drops the client when its write under way is older than
  /// `write_timeout`, else sends what is due.
  void pace(Clock::time_point now, std::chrono::duration<double> write_timeout);
  /// Closes the connection at once (no close frames); the host hears of it.
  void drop();

 private:
  void read_messages();
  /// Starts the next write when idle: a text, else frames, else the end.
  void send();
  void send_frames();
  /// Closes the WebSocket properly (close frames both ways), so that the browser reads
  /// everything sent before, then drops the client.
  void close();
  template <typename Buffer, typename Handler>
  void start_write(ClientEvent event, const Buffer& buffer, bool binary, Handler&& on_written);
  void transition(ClientEvent event) { state_ = next_client_state(state_, event); }

  boost::beast::websocket::stream<boost::beast::tcp_stream> stream_;
  ViewClientHost& host_;
  const FrameBroadcaster& frames_;
  std::size_t max_frames_per_message_;
  boost::beast::flat_buffer incoming_;
  std::vector<double> outgoing_;   ///< Frames of the message being written (reused).
  std::string text_;               ///< The text message being written.
  std::deque<std::string> texts_;  ///< Text messages waiting, oldest first.
  std::uint64_t id_ = 0;
  std::uint64_t last_frame_ = 0;  ///< Number of the last frame sent.
  ClientState state_ = ClientState::kHandshaking;
  Clock::time_point write_started_;  ///< When the write (or close) under way started.
};

}  // namespace upkie_rl
