#include "view/view_server.hpp"

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <iostream>
#include <list>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>
#include <unordered_set>
#include <vector>

#include "view/client_state.hpp"
#include "view/drive_control.hpp"
#include "view/origin_check.hpp"
#include "view/view_error.hpp"
#include "view/view_session.hpp"
#include "view/viewer_page.hpp"

namespace upkie_rl {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = net::ip::tcp;
using SteadyClock = std::chrono::steady_clock;

void ViewServerConfig::validate() const {
  if (port < 0 || port > 65535) {
    throw ViewError("viewer port " + std::to_string(port) + " is not in [0, 65535]");
  }
  if (!(send_period > 0.0 && send_period <= 1.0)) {
    throw ViewError("viewer send_period must be in (0, 1] s");
  }
  if (max_frames_per_message == 0) throw ViewError("viewer max_frames_per_message must be > 0");
  if (!(write_timeout > 0.0)) throw ViewError("viewer write_timeout must be positive");
  if (max_clients == 0) throw ViewError("viewer max_clients must be > 0");
  if (max_connections == 0 || max_connections > 65536) {
    throw ViewError("viewer max_connections " + std::to_string(max_connections) +
                    " is not in [1, 65536]");
  }
  if (!(idle_timeout > 0.0 && idle_timeout <= 3600.0)) {
    throw ViewError("viewer idle_timeout must be in (0, 3600] s");
  }
}

namespace {

/// Wait before accepting again after accept failed (out of file descriptors): the pending
/// connection stays queued, so an immediate retry would fail at once, again and again.
constexpr auto kAcceptRetryDelay = std::chrono::milliseconds(200);
/// Text messages waiting for one browser beyond this are dropped (a page that floods the
/// server with refused messages must not grow its queue without bound).
constexpr std::size_t kMaxQueuedTexts = 64;

/// The value of header `field` of `request`, empty when it has none.
std::string_view header_value(const http::request<http::string_body>& request, http::field field) {
  const auto found = request.find(field);
  return found == request.end() ? std::string_view()
                                : std::string_view(found->value().data(), found->value().size());
}

}  // namespace

/// One browser's WebSocket: frames are written by the server's timer, one message at a
/// time; a read loop notices when the browser goes away. Its `state` (view/client_state.hpp)
/// changes only through Impl::transition.
struct ViewClient : std::enable_shared_from_this<ViewClient> {
  explicit ViewClient(tcp::socket&& socket) : stream(std::move(socket)) {}

  websocket::stream<beast::tcp_stream> stream;
  beast::flat_buffer incoming;
  std::vector<double> outgoing;   ///< Frames of the message being written (reused).
  std::string text;               ///< The text message being written.
  std::deque<std::string> texts;  ///< Text messages waiting (driving replies), oldest first.
  std::uint64_t id = 0;           ///< Numbers the browsers for the DriveControl.
  std::uint64_t last_frame = 0;   ///< Number of the last frame sent.
  ClientState state = ClientState::kHandshaking;
  SteadyClock::time_point write_started;  ///< When the write (or close) under way started.
};

struct ViewServer::Impl {
  Impl(ViewServerConfig config_in, std::string session_json_in,
       std::shared_ptr<const FrameBroadcaster> frames_in, std::shared_ptr<DriveControl> drive_in)
      : config(std::move(config_in)),
        session_json(std::move(session_json_in)),
        page(served_viewer_page()),
        frames(std::move(frames_in)),
        drive(std::move(drive_in)),
        acceptor(io),
        timer(io),
        accept_retry(io) {}

  ViewServerConfig config;
  std::string session_json;
  std::string page;
  std::shared_ptr<const FrameBroadcaster> frames;
  std::shared_ptr<DriveControl> drive;  ///< Null unless pages may drive.
  // Open HTTP connections (their streams' deleter counts them out); before `io`, whose
  // destruction runs those deleters.
  std::size_t http_connections = 0;
  net::io_context io;
  tcp::acceptor acceptor;
  net::steady_timer timer;
  net::steady_timer accept_retry;
  bool ticking = false;  // the frame timer runs only while browsers are connected
  bool accept_failing = false;
  bool loopback = true;  ///< Listening on a loopback address (is_allowed_host).
  std::thread thread;
  std::string url;
  int port = 0;

  // Owned by the io thread.
  std::list<std::shared_ptr<ViewClient>> clients;
  std::uint64_t next_client_id = 1;
  std::string end_reason;
  bool ended = false;
  // The clients connected when end() was carried out that are not closed yet.
  std::unordered_set<const ViewClient*> end_audience;

  // Read from any thread.
  std::atomic<std::size_t> num_clients{0};
  std::atomic<std::uint64_t> clients_connected{0}, messages_sent{0}, frames_sent{0},
      frames_skipped{0}, http_requests{0};
  mutable std::mutex wait_mutex;
  mutable std::condition_variable changed;
  // Under wait_mutex: set when end() is carried out, with the number of browsers that were
  // connected then and have neither had the end message nor gone away.
  bool end_posted = false;
  std::size_t awaiting_end = 0;

  void listen();
  void accept();
  /// config.idle_timeout as a clock duration.
  SteadyClock::duration idle_timeout() const {
    return std::chrono::duration_cast<SteadyClock::duration>(
        std::chrono::duration<double>(config.idle_timeout));
  }
  /// Starts the frame timer unless it runs.
  void start_ticking();
  void read_request(const std::shared_ptr<beast::tcp_stream>& stream,
                    const std::shared_ptr<beast::flat_buffer>& buffer);
  void answer(const std::shared_ptr<beast::tcp_stream>& stream,
              const std::shared_ptr<beast::flat_buffer>& buffer,
              const http::request<http::string_body>& request);
  void upgrade(const std::shared_ptr<beast::tcp_stream>& stream,
               const http::request<http::string_body>& request);
  /// Answers a request (a WebSocket handshake or a page's) with a plain HTTP `status` and
  /// `reason`, then closes.
  void refuse(const std::shared_ptr<beast::tcp_stream>& stream,
              const http::request<http::string_body>& request, http::status status,
              const char* reason);
  void read_messages(const std::shared_ptr<ViewClient>& client);
  /// Queues a text message for `client` and sends it as soon as its writes allow.
  void queue_text(const std::shared_ptr<ViewClient>& client, std::string text);
  /// Queues every browser's drive status (its role changed, or the pause).
  void send_drive_statuses();
  /// Sends the driver the acknowledgement DriveControl queued.
  void send_acknowledgement();
  void drop(const std::shared_ptr<ViewClient>& client);
  void tick();
  void send(const std::shared_ptr<ViewClient>& client);
  /// Closes the WebSocket properly (close frames both ways), so that the browser reads
  /// everything sent before, then forgets the client.
  void close(const std::shared_ptr<ViewClient>& client);
  void notify();
  /// Counts one client out of those end() waits for.
  void end_delivered();
  /// Moves `client` to its next state (view/client_state.hpp).
  static void transition(ViewClient& client, ClientEvent event) {
    client.state = next_client_state(client.state, event);
  }
  /// Starts writing `buffer` as the write `event` says (text or binary).
  template <typename Buffer, typename Handler>
  static void start_write(const std::shared_ptr<ViewClient>& client, ClientEvent event,
                          const Buffer& buffer, bool binary, Handler&& on_written) {
    transition(*client, event);
    client->stream.binary(binary);
    client->write_started = SteadyClock::now();
    client->stream.async_write(buffer, std::forward<Handler>(on_written));
  }
};

void ViewServer::Impl::listen() {
  beast::error_code error;
  const net::ip::address address = net::ip::make_address(config.host, error);
  if (error) throw ViewError("viewer host \"" + config.host + "\" is not an IP address");
  const tcp::endpoint endpoint(address, static_cast<unsigned short>(config.port));
  const std::string where = config.host + ":" + std::to_string(config.port);
  acceptor.open(endpoint.protocol(), error);
  if (!error) acceptor.set_option(net::socket_base::reuse_address(true), error);
  if (!error) acceptor.bind(endpoint, error);
  if (error == net::error::address_in_use) {
    throw ViewError("the viewer cannot listen on " + where +
                    ": the port is in use (another viewer?); choose another port, or 0 for any "
                    "free one");
  }
  if (!error) acceptor.listen(net::socket_base::max_listen_connections, error);
  if (error) throw ViewError("the viewer cannot listen on " + where + ": " + error.message());
  port = acceptor.local_endpoint().port();
  loopback = address.is_loopback();
  const std::string host = address.is_v6() ? "[" + config.host + "]" : config.host;
  url = "http://" + host + ":" + std::to_string(port) + "/";
}

void ViewServer::Impl::accept() {
  acceptor.async_accept([this](beast::error_code error, tcp::socket socket) {
    if (error == net::error::operation_aborted) return;
    if (error) {
      // Out of descriptors (EMFILE, ENFILE) or the like: refuse for now, retry later; said
      // once per spell of failures.
      if (!accept_failing) {
        std::cerr << "viewer: cannot accept connections (" << error.message()
                  << "); retrying every " << kAcceptRetryDelay.count() << " ms" << std::endl;
      }
      accept_failing = true;
      accept_retry.expires_after(kAcceptRetryDelay);
      accept_retry.async_wait([this](beast::error_code wait_error) {
        if (!wait_error) accept();
      });
      return;
    }
    accept_failing = false;
    if (http_connections + clients.size() >= config.max_connections) {
      beast::error_code ignored;
      socket.close(ignored);  // over the cap: refused at once, holding nothing
    } else {
      ++http_connections;
      const auto stream = std::shared_ptr<beast::tcp_stream>(
          new beast::tcp_stream(std::move(socket)), [this](beast::tcp_stream* closed) {
            delete closed;
            --http_connections;
          });
      read_request(stream, std::make_shared<beast::flat_buffer>());
    }
    accept();
  });
}

void ViewServer::Impl::read_request(const std::shared_ptr<beast::tcp_stream>& stream,
                                    const std::shared_ptr<beast::flat_buffer>& buffer) {
  auto parser = std::make_shared<http::request_parser<http::string_body>>();
  parser->header_limit(kViewMaxRequestBytes);
  parser->body_limit(kViewMaxRequestBytes);
  stream->expires_after(idle_timeout());
  http::async_read(*stream, *buffer, *parser,
                   [this, stream, buffer, parser](beast::error_code error, std::size_t) {
                     if (error) return;  // closed, timed out or malformed: drop the connection
                     ++http_requests;
                     http::request<http::string_body> request = parser->release();
                     if (!is_allowed_host(header_value(request, http::field::host), loopback)) {
                       refuse(stream, request, http::status::forbidden,
                              "the Host header names another site; this viewer "
                              "listens on a loopback address (127.0.0.1, localhost)\n");
                     } else if (websocket::is_upgrade(request)) {
                       upgrade(stream, request);
                     } else {
                       answer(stream, buffer, request);
                     }
                   });
}

void ViewServer::Impl::answer(const std::shared_ptr<beast::tcp_stream>& stream,
                              const std::shared_ptr<beast::flat_buffer>& buffer,
                              const http::request<http::string_body>& request) {
  auto response = std::make_shared<http::response<http::string_body>>();
  response->version(request.version());
  response->keep_alive(request.keep_alive());
  response->set(http::field::server, "upkie-rl");
  response->set(http::field::cache_control, "no-store");
  const std::string_view target(request.target().data(), request.target().size());
  const std::string_view path = target.substr(0, target.find('?'));
  if (request.method() != http::verb::get && request.method() != http::verb::head) {
    response->result(http::status::method_not_allowed);
    response->set(http::field::content_type, "text/plain");
    response->body() = "only GET and HEAD\n";
  } else if (path == "/" || path == "/index.html") {
    response->set(http::field::content_type, "text/html; charset=utf-8");
    response->body() = page;
  } else if (path == "/viewer.js") {
    response->set(http::field::content_type, "text/javascript; charset=utf-8");
    response->body() = std::string(viewer_script());
  } else if (path == "/session.json") {
    response->set(http::field::content_type, "application/json");
    response->body() = session_json;
  } else {
    response->result(http::status::not_found);
    response->set(http::field::content_type, "text/plain");
    response->body() = "not found\n";
  }
  response->prepare_payload();
  if (request.method() == http::verb::head) response->body().clear();
  stream->expires_after(idle_timeout());
  http::async_write(*stream, *response,
                    [this, stream, buffer, response](beast::error_code error, std::size_t) {
                      if (error || !response->keep_alive()) {
                        beast::error_code ignored;
                        stream->socket().shutdown(tcp::socket::shutdown_send, ignored);
                        return;
                      }
                      read_request(stream, buffer);
                    });
}

void ViewServer::Impl::refuse(const std::shared_ptr<beast::tcp_stream>& stream,
                              const http::request<http::string_body>& request, http::status status,
                              const char* reason) {
  auto response = std::make_shared<http::response<http::string_body>>(status, request.version());
  response->set(http::field::content_type, "text/plain");
  response->body() = reason;
  response->prepare_payload();
  http::async_write(*stream, *response, [stream, response](beast::error_code, std::size_t) {
    beast::error_code ignored;
    stream->socket().shutdown(tcp::socket::shutdown_send, ignored);
  });
}

void ViewServer::Impl::upgrade(const std::shared_ptr<beast::tcp_stream>& stream,
                               const http::request<http::string_body>& request) {
  const std::string_view target(request.target().data(), request.target().size());
  const bool frames_path = target.substr(0, target.find('?')) == kViewFramesPath;
  if (!is_same_origin(header_value(request, http::field::origin),
                      header_value(request, http::field::host))) {
    refuse(stream, request, http::status::forbidden,
           "a page of another site may not open the viewer's WebSocket\n");
    return;
  }
  if (!frames || !frames_path || clients.size() >= config.max_clients) {
    // Not a frame stream here, or too many browsers: a plain HTTP refusal.
    const bool busy = frames && frames_path;
    refuse(stream, request, busy ? http::status::service_unavailable : http::status::not_found,
           busy ? "too many viewers\n" : "no frame stream here\n");
    return;
  }
  stream->expires_never();  // the websocket stream keeps its own timeouts
  auto client = std::make_shared<ViewClient>(stream->release_socket());
  // Small messages (a driving acknowledgement) go out at once: with Nagle's algorithm one
  // written right after another waits for the browser's delayed ACK (40 ms on Linux).
  beast::error_code ignored;
  beast::get_lowest_layer(client->stream).socket().set_option(tcp::no_delay(true), ignored);
  client->stream.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
  client->stream.read_message_max(kViewMaxRequestBytes);
  client->stream.binary(true);
  // Start with what the ring still holds, so that the plots fill at once.
  const std::uint64_t newest = frames->newest();
  client->last_frame = newest > frames->capacity() ? newest - frames->capacity() : 0;
  // Kept alive until the handshake is over.
  auto held = std::make_shared<http::request<http::string_body>>(request);
  client->stream.async_accept(*held, [this, client, held](beast::error_code error) {
    if (error) return;
    transition(*client, ClientEvent::kAccepted);
    client->id = next_client_id++;
    clients.push_back(client);
    if (drive) queue_text(client, drive->status_message(client->id));
    ++clients_connected;
    num_clients.store(clients.size());
    notify();
    read_messages(client);
    send(client);
    start_ticking();
  });
}

void ViewServer::Impl::read_messages(const std::shared_ptr<ViewClient>& client) {
  client->stream.async_read(client->incoming, [this, client](beast::error_code error, std::size_t) {
    if (error) {
      drop(client);
      return;
    }
    if (drive && !client->stream.got_binary()) {
      const auto data = client->incoming.cdata();
      const DriveControl::Reply reply = drive->receive(
          client->id, std::string_view(static_cast<const char*>(data.data()), data.size()),
          SteadyClock::now());
      if (!reply.to_sender.empty()) queue_text(client, reply.to_sender);
      if (reply.status_changed) send_drive_statuses();
    }
    client->incoming.clear();  // a page that does not drive sends nothing the server needs
    read_messages(client);
  });
}

void ViewServer::Impl::queue_text(const std::shared_ptr<ViewClient>& client, std::string text) {
  if (!is_open(client->state) || client->texts.size() >= kMaxQueuedTexts) return;
  client->texts.push_back(std::move(text));
  send(client);
}

void ViewServer::Impl::send_drive_statuses() {
  const std::vector<std::shared_ptr<ViewClient>> current(clients.begin(), clients.end());
  for (const std::shared_ptr<ViewClient>& client : current) {
    queue_text(client, drive->status_message(client->id));
  }
}

void ViewServer::Impl::send_acknowledgement() {
  auto acknowledgement = drive->take_acknowledgement();
  if (!acknowledgement) return;
  for (const std::shared_ptr<ViewClient>& client : clients) {
    if (client->id == acknowledgement->first) {
      queue_text(client, std::move(acknowledgement->second));
      return;
    }
  }
}

void ViewServer::Impl::drop(const std::shared_ptr<ViewClient>& client) {
  if (!is_open(client->state)) return;
  transition(*client, ClientEvent::kDropped);
  beast::error_code ignored;
  beast::get_lowest_layer(client->stream).socket().close(ignored);
  clients.remove(client);
  num_clients.store(clients.size());
  if (drive && drive->disconnect(client->id)) send_drive_statuses();
  if (end_audience.erase(client.get()) > 0) end_delivered();
  notify();
}

void ViewServer::Impl::tick() {
  const auto now = SteadyClock::now();
  const auto timeout = std::chrono::duration<double>(config.write_timeout);
  // Copy: send() and drop() may change the list.
  const std::vector<std::shared_ptr<ViewClient>> current(clients.begin(), clients.end());
  for (const std::shared_ptr<ViewClient>& client : current) {
    if (is_writing(client->state)) {
      if (now - client->write_started > timeout) drop(client);
      continue;
    }
    send(client);
  }
  // Idle without browsers: no timer, no wake-ups, until the next one connects.
  if (clients.empty()) {
    ticking = false;
    return;
  }
  timer.expires_after(std::chrono::duration_cast<SteadyClock::duration>(
      std::chrono::duration<double>(config.send_period)));
  timer.async_wait([this](beast::error_code error) {
    if (!error) tick();
  });
}

void ViewServer::Impl::start_ticking() {
  if (ticking || !frames) return;
  ticking = true;
  tick();
}

void ViewServer::Impl::send(const std::shared_ptr<ViewClient>& client) {
  if (client->state != ClientState::kIdle) return;
  const auto on_text_written = [this, client](beast::error_code error, std::size_t) {
    if (error) {
      drop(client);
      return;
    }
    transition(*client, ClientEvent::kWritten);
    send(client);  // the next text, or frames
  };
  if (!client->texts.empty()) {
    client->text = std::move(client->texts.front());
    client->texts.pop_front();
    start_write(client, ClientEvent::kTextStarted, net::buffer(client->text), false,
                on_text_written);
    return;
  }
  if (!frames) return;
  client->outgoing.clear();
  const FrameBroadcaster::Collected collected =
      frames->collect(client->last_frame, config.max_frames_per_message, client->outgoing);
  client->last_frame = collected.newest;
  frames_skipped += collected.skipped;
  const auto on_written = [this, client](beast::error_code error, std::size_t) {
    if (error) {
      drop(client);
      return;
    }
    transition(*client, ClientEvent::kWritten);
    if (client->state == ClientState::kClosing) close(client);  // the end message went out
  };
  if (!client->outgoing.empty()) {
    const std::size_t count = client->outgoing.size() / frames->frame_size();
    ++messages_sent;
    frames_sent += count;
    start_write(client, ClientEvent::kFramesStarted,
                net::buffer(client->outgoing.data(), client->outgoing.size() * sizeof(double)),
                true, on_written);
  } else if (ended) {
    client->text = nlohmann::json{{"type", "end"}, {"reason", end_reason}}.dump();
    start_write(client, ClientEvent::kEndStarted, net::buffer(client->text), false, on_written);
  }
}

void ViewServer::Impl::end_delivered() {
  const std::lock_guard lock(wait_mutex);
  if (awaiting_end > 0) --awaiting_end;
  changed.notify_all();
}

void ViewServer::Impl::close(const std::shared_ptr<ViewClient>& client) {
  client->write_started = SteadyClock::now();  // kClosing: nothing more is sent
  client->stream.async_close(websocket::close_code::normal,
                             [this, client](beast::error_code) { drop(client); });
}

void ViewServer::Impl::notify() {
  const std::lock_guard lock(wait_mutex);
  changed.notify_all();
}

ViewServer::ViewServer(const ViewServerConfig& config, std::string session_json,
                       std::shared_ptr<const FrameBroadcaster> frames,
                       std::shared_ptr<DriveControl> drive)
    : impl_(std::make_unique<Impl>(config, std::move(session_json), std::move(frames),
                                   std::move(drive))) {
  config.validate();
  if (impl_->drive && !impl_->frames) throw ViewError("a driven view needs a frame stream");
  if (impl_->drive) {
    // Called on the simulation's thread: the acknowledgement goes out on the server's.
    impl_->drive->set_applied_listener(
        [impl = impl_.get()] { net::post(impl->io, [impl] { impl->send_acknowledgement(); }); });
  }
  impl_->listen();
  impl_->accept();
  impl_->thread = std::thread([impl = impl_.get()] {
    // A failure of the viewer must not end the process that publishes (a training): it is
    // reported and the viewer stops serving.
    try {
      impl->io.run();
    } catch (const std::exception& error) {
      std::cerr << "viewer: stopped after an error: " << error.what()
                << " (the run goes on without it)" << std::endl;
    }
  });
}

ViewServer::~ViewServer() {
  if (impl_->drive) impl_->drive->set_applied_listener(nullptr);
  impl_->io.stop();
  if (impl_->thread.joinable()) impl_->thread.join();
}

int ViewServer::port() const { return impl_->port; }

std::string ViewServer::url() const { return impl_->url; }

std::size_t ViewServer::num_clients() const { return impl_->num_clients.load(); }

ViewServerStatistics ViewServer::statistics() const {
  return {impl_->clients_connected.load(), impl_->messages_sent.load(), impl_->frames_sent.load(),
          impl_->frames_skipped.load(), impl_->http_requests.load()};
}

bool ViewServer::wait_for_clients(std::size_t count, std::chrono::milliseconds timeout,
                                  const std::atomic<bool>* interrupt) const {
  const auto deadline = SteadyClock::now() + timeout;
  std::unique_lock lock(impl_->wait_mutex);
  while (impl_->num_clients.load() < count) {
    if ((interrupt && interrupt->load()) || SteadyClock::now() >= deadline) return false;
    // Short waits: the interrupt flag is set by a signal handler, which cannot notify.
    impl_->changed.wait_for(lock, std::chrono::milliseconds(50));
  }
  return true;
}

void ViewServer::end(const std::string& reason, std::chrono::milliseconds timeout) {
  if (!impl_->frames) return;
  net::post(impl_->io, [impl = impl_.get(), reason] {
    impl->end_reason = reason;
    impl->ended = true;
    impl->end_audience.clear();
    for (const std::shared_ptr<ViewClient>& client : impl->clients) {
      impl->end_audience.insert(client.get());
    }
    const std::lock_guard lock(impl->wait_mutex);
    impl->end_posted = true;
    impl->awaiting_end = impl->clients.size();
    impl->changed.notify_all();
  });
  // The end message follows the last frames at the next ticks.
  std::unique_lock lock(impl_->wait_mutex);
  impl_->changed.wait_for(lock, timeout,
                          [this] { return impl_->end_posted && impl_->awaiting_end == 0; });
}

}  // namespace upkie_rl
