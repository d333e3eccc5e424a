#pragma once
/// @file
/// ViewServer: the viewer's HTTP and WebSocket server (Boost.Beast), on a thread of its own.
/// It serves the page, its script and the session document, and sends every connected
/// browser the frames of a FrameBroadcaster. A browser that reads slowly gets fewer frames; one
/// that stops reading is disconnected; the simulation that publishes never waits for either.

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "view/drive_control.hpp"
#include "view/frame_broadcaster.hpp"

namespace upkie_rl {

/// Largest HTTP request or WebSocket message taken from a browser: the page sends its
/// requests and, when it drives, small JSON messages.
inline constexpr std::size_t kViewMaxRequestBytes = std::size_t{16} * 1024;

/// Settings of a ViewServer.
struct ViewServerConfig {
  std::string host = "127.0.0.1";  ///< IPv4 or IPv6 address to listen on.
  int port = 7000;                 ///< TCP port; 0 picks a free one (see ViewServer::port()).
  /// Time between two messages of frames to one browser [s]: a browser draws at 60 Hz, and
  /// each message carries every frame published since the last one (at most
  /// max_frames_per_message, the newest).
  double send_period = 0.02;
  std::size_t max_frames_per_message = 256;
  /// A browser that has not taken a message within this time is disconnected [s].
  double write_timeout = 10.0;
  std::size_t max_clients = 64;  ///< WebSocket clients beyond this are refused (HTTP 503).
  /// Open TCP connections (HTTP and WebSocket together) beyond this are closed as soon as
  /// accepted, so that idle connections cannot exhaust the process's file descriptors
  /// (which the training needs for its checkpoints).
  std::size_t max_connections = 128;
  /// An HTTP connection that has not sent a whole request within this time is closed [s].
  double idle_timeout = 10.0;

  /// @throws ViewError naming a setting out of range.
  void validate() const;
};

/// Counters of a ViewServer, readable from any thread.
struct ViewServerStatistics {
  std::uint64_t clients_connected = 0;  ///< Since the start.
  std::uint64_t messages_sent = 0;      ///< Of frames, to all clients.
  std::uint64_t frames_sent = 0;        ///< Summed over clients.
  std::uint64_t frames_skipped = 0;     ///< Frames a client did not get (it was too slow).
  std::uint64_t http_requests = 0;
};

class ViewServer {
 public:
  /// Listens, then serves on its own thread until destroyed.
  /// @param session_json The session document (view_session_json).
  /// @param frames Frames to stream, or null (a replay: the page has every frame).
  /// @param drive When set, pages may drive: their text messages go to it, and each page is
  ///        told its role (DriveControl); needs `frames`.
  /// @throws ViewError naming the address and the cause when it cannot listen (a busy
  ///         port, a bad address, no permission).
  ViewServer(const ViewServerConfig& config, std::string session_json,
             std::shared_ptr<const FrameBroadcaster> frames,
             std::shared_ptr<DriveControl> drive = nullptr);
  /// Closes every connection and joins the thread.
  ~ViewServer();
  ViewServer(const ViewServer&) = delete;
  ViewServer& operator=(const ViewServer&) = delete;

  /// The port listened on (the one the system chose for port 0).
  int port() const;
  /// http://host:port/ (IPv6 hosts in brackets).
  std::string url() const;
  /// WebSocket clients connected now.
  std::size_t num_clients() const;
  ViewServerStatistics statistics() const;

  /// Waits until `count` browsers are connected, `timeout` passes or `interrupt` becomes
  /// true; returns whether they are.
  bool wait_for_clients(std::size_t count, std::chrono::milliseconds timeout,
                        const std::atomic<bool>* interrupt = nullptr) const;

  /// Tells every browser, now and later, that the run is over and why (a text message
  /// {"type": "end", "reason": ...} after the remaining frames), and waits up to `timeout`
  /// for those connected to have it.
  void end(const std::string& reason,
           std::chrono::milliseconds timeout = std::chrono::milliseconds(1000));

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace upkie_rl
