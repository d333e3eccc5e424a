#include "view/view_server.hpp"

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <iostream>
#include <list>
#include <thread>
#include <vector>

#include "view/drive_control.hpp"
#include "view/end_notice.hpp"
#include "view/frame_pacer.hpp"
#include "view/http_connection.hpp"
#include "view/view_client.hpp"
#include "view/view_error.hpp"
#include "view/view_server_monitor.hpp"
#include "view/view_session.hpp"
#include "view/viewer_routes.hpp"

namespace upkie_rl {

namespace net = boost::asio;
namespace http = boost::beast::http;
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

SteadyClock::duration to_clock_duration(double seconds) {
  return std::chrono::duration_cast<SteadyClock::duration>(std::chrono::duration<double>(seconds));
}

}  // namespace

/// The server: listens, accepts connections (HttpConnection) up to the cap, admits
/// WebSocket clients (ViewClient) and keeps them, paces their frames (FramePacer), and
/// connects them to the DriveControl and the end of the run (EndNotice). Every member but
/// the monitor lives on the io thread and takes no lock; other threads reach the io thread
/// through net::post, and read the monitor (view/view_server_monitor.hpp).
struct ViewServer::Impl final : ViewClientHost {
  Impl(ViewServerConfig config_in, std::string session_json,
       std::shared_ptr<const FrameBroadcaster> frames_in, std::shared_ptr<DriveControl> drive_in)
      : config(std::move(config_in)),
        routes(std::move(session_json)),
        frames(std::move(frames_in)),
        drive(std::move(drive_in)),
        acceptor(io),
        accept_retry(io),
        pacer(io, to_clock_duration(config.send_period), [this] { return tick(); }) {
    handlers.on_request = [this] { monitor.http_request(); };
    handlers.on_upgrade = [this](const std::shared_ptr<HttpConnection>& connection,
                                 const HttpRequest& request) { upgrade(connection, request); };
  }

  ViewServerConfig config;
  ViewerRoutes routes;
  std::shared_ptr<const FrameBroadcaster> frames;
  std::shared_ptr<DriveControl> drive;  ///< Null unless pages may drive.
  ViewServerMonitor monitor;
  // What connections refer to, and the count of those open; before `io`, whose
  // destruction ends the connections it still holds.
  HttpConnection::Handlers handlers;
  HttpConnection::Settings connection_settings;
  std::size_t http_connections = 0;
  net::io_context io;
  tcp::acceptor acceptor;
  net::steady_timer accept_retry;
  bool accept_failing = false;
  FramePacer pacer;
  std::list<std::shared_ptr<ViewClient>> clients;
  std::uint64_t next_client_id = 1;
  EndNotice end_notice;
  std::thread thread;
  std::string url;
  int port = 0;

  void listen();
  void accept();
  /// Takes a new TCP connection, or closes it at once when max_connections are open.
  void take(tcp::socket socket);
  /// A WebSocket handshake: becomes a client when it asks for the frame stream and there
  /// is room; refused with a plain HTTP status otherwise.
  void upgrade(const std::shared_ptr<HttpConnection>& connection, const HttpRequest& request);
  /// The pacer's tick: every client sends what is due; returns whether clients remain.
  bool tick();
  /// Queues every browser's drive status (its role changed, or the pause).
  void send_drive_statuses();
  /// Sends the driver the acknowledgement DriveControl queued.
  void send_acknowledgement();
  /// The end of the run, posted to the clients connected now.
  void post_end(const std::string& reason);

  // ViewClientHost
  void opened(const std::shared_ptr<ViewClient>& client) override;
  void received(ViewClient& client, std::string_view text) override;
  void dropped(const std::shared_ptr<ViewClient>& client) override;
  void frames_collected(std::size_t count, std::uint64_t skipped) override {
    monitor.frames_collected(count, skipped);
  }
  const std::string* end_message() const override { return end_notice.message(); }
};

void ViewServer::Impl::listen() {
  boost::beast::error_code error;
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
  connection_settings = {address.is_loopback(), to_clock_duration(config.idle_timeout)};
  const std::string host = address.is_v6() ? "[" + config.host + "]" : config.host;
  url = "http://" + host + ":" + std::to_string(port) + "/";
}

void ViewServer::Impl::accept() {
  acceptor.async_accept([this](boost::beast::error_code error, tcp::socket socket) {
    if (error == net::error::operation_aborted) return;
    if (error) {
      // Out of descriptors (EMFILE, ENFILE) or the like: refuse for now, retry later; said
      // once per spell of failures, in one write: the line stays whole among the
      // publisher's own output, and no stream member function runs while descriptors are
      // out (UBSan's vptr check on one reports a false "invalid vptr" then: its runtime
      // probes the object's memory through a pipe() that fails with EMFILE).
      if (!accept_failing) {
        std::cerr << "viewer: cannot accept connections (" + error.message() +
                         "); retrying every " + std::to_string(kAcceptRetryDelay.count()) + " ms\n";
      }
      accept_failing = true;
      accept_retry.expires_after(kAcceptRetryDelay);
      accept_retry.async_wait([this](boost::beast::error_code wait_error) {
        if (!wait_error) accept();
      });
      return;
    }
    accept_failing = false;
    take(std::move(socket));
    accept();
  });
}

void ViewServer::Impl::take(tcp::socket socket) {
  if (http_connections + clients.size() >= config.max_connections) {
    boost::beast::error_code ignored;
    socket.close(ignored);  // over the cap: refused at once, holding nothing
    return;
  }
  std::make_shared<HttpConnection>(std::move(socket), routes, handlers, connection_settings,
                                   http_connections)
      ->start();
}

void ViewServer::Impl::upgrade(const std::shared_ptr<HttpConnection>& connection,
                               const HttpRequest& request) {
  const bool frames_path = request_path(request) == kViewFramesPath;
  if (!frames || !frames_path || clients.size() >= config.max_clients) {
    // Not a frame stream here, or too many browsers: a plain HTTP refusal.
    const bool busy = frames && frames_path;
    connection->refuse(request, busy ? http::status::service_unavailable : http::status::not_found,
                       busy ? "too many viewers\n" : "no frame stream here\n");
    return;
  }
  std::make_shared<ViewClient>(connection->release_socket(), *this, *frames,
                               config.max_frames_per_message)
      ->open(request);
}

void ViewServer::Impl::opened(const std::shared_ptr<ViewClient>& client) {
  client->set_id(next_client_id++);
  clients.push_back(client);
  if (drive) client->queue_text(drive->status_message(client->id()));
  monitor.client_opened(clients.size());
  pacer.start();
}

void ViewServer::Impl::received(ViewClient& client, std::string_view text) {
  if (!drive) return;  // a page that does not drive sends nothing the server needs
  const DriveControl::Reply reply = drive->receive(client.id(), text, SteadyClock::now());
  if (!reply.to_sender.empty()) client.queue_text(reply.to_sender);
  if (reply.status_changed) send_drive_statuses();
}

void ViewServer::Impl::dropped(const std::shared_ptr<ViewClient>& client) {
  clients.remove(client);
  if (drive && drive->disconnect(client->id())) send_drive_statuses();
  if (end_notice.delivered(client.get())) monitor.end_delivered();
  monitor.client_closed(clients.size());
}

bool ViewServer::Impl::tick() {
  const auto now = SteadyClock::now();
  const auto timeout = std::chrono::duration<double>(config.write_timeout);
  // Copy: a client dropped leaves the list.
  const std::vector<std::shared_ptr<ViewClient>> current(clients.begin(), clients.end());
  for (const std::shared_ptr<ViewClient>& client : current) client->pace(now, timeout);
  // Idle without browsers: no timer, no wake-ups, until the next one connects.
  return !clients.empty();
}

void ViewServer::Impl::send_drive_statuses() {
  const std::vector<std::shared_ptr<ViewClient>> current(clients.begin(), clients.end());
  for (const std::shared_ptr<ViewClient>& client : current) {
    client->queue_text(drive->status_message(client->id()));
  }
}

void ViewServer::Impl::send_acknowledgement() {
  auto acknowledgement = drive->take_acknowledgement();
  if (!acknowledgement) return;
  for (const std::shared_ptr<ViewClient>& client : clients) {
    if (client->id() == acknowledgement->first) {
      client->queue_text(std::move(acknowledgement->second));
      return;
    }
  }
}

void ViewServer::Impl::post_end(const std::string& reason) {
  EndNotice::Audience audience;
  for (const std::shared_ptr<ViewClient>& client : clients) audience.insert(client.get());
  end_notice.post(reason, std::move(audience));
  monitor.end_posted(clients.size());
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

std::size_t ViewServer::num_clients() const { return impl_->monitor.num_clients(); }

ViewServerStatistics ViewServer::statistics() const { return impl_->monitor.statistics(); }

bool ViewServer::wait_for_clients(std::size_t count, std::chrono::milliseconds timeout,
                                  const std::atomic<bool>* interrupt) const {
  return impl_->monitor.wait_for_clients(count, timeout, interrupt);
}

void ViewServer::end(const std::string& reason, std::chrono::milliseconds timeout) {
  if (!impl_->frames) return;
  net::post(impl_->io, [impl = impl_.get(), reason] { impl->post_end(reason); });
  // The end message follows the last frames at the next ticks.
  impl_->monitor.wait_for_end(timeout);
}

}  // namespace upkie_rl
