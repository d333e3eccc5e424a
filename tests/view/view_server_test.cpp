#include "view/view_server.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <cstring>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>
#include <vector>

#include "common/frame_client.hpp"
#include "view/view_error.hpp"
#include "view/viewer_page.hpp"

namespace upkie_rl {
namespace {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = net::ip::tcp;
using namespace std::chrono_literals;

constexpr std::size_t kFrameSize = 4;
const std::string kSession = R"({"mode":"live","websocket":"/frames"})";

ViewServerConfig any_port() {
  ViewServerConfig config;
  config.port = 0;
  config.send_period = 0.005;
  return config;
}

std::vector<double> frame_of(double value) { return {value, value + 0.25, -value, 1.0}; }

/// GET (or another method) on the server; returns the status and body.
std::pair<int, std::string> request(int port, const std::string& target,
                                    http::verb method = http::verb::get,
                                    const std::string& host = "127.0.0.1") {
  net::io_context io;
  beast::tcp_stream stream(io);
  stream.connect(
      tcp::endpoint(net::ip::make_address("127.0.0.1"), static_cast<unsigned short>(port)));
  http::request<http::string_body> req(method, target, 11);
  req.set(http::field::host, host);
  http::write(stream, req);
  beast::flat_buffer buffer;
  http::response_parser<http::string_body> parser;
  parser.body_limit(16 * 1024 * 1024);
  if (method == http::verb::head) parser.skip(true);
  http::read(stream, buffer, parser);
  return {static_cast<int>(parser.get().result_int()), parser.get().body()};
}

bool eventually(const std::function<bool()>& condition,
                std::chrono::milliseconds timeout = 15000ms) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    if (condition()) return true;
    std::this_thread::sleep_for(10ms);
  }
  return condition();
}

TEST(ViewServer, ServesThePageItsScriptAndTheSession) {
  const ViewServer server(any_port(), kSession, nullptr);
  ASSERT_GT(server.port(), 0);
  EXPECT_EQ(server.url(), "http://127.0.0.1:" + std::to_string(server.port()) + "/");
  const auto [page_status, page] = request(server.port(), "/");
  EXPECT_EQ(page_status, 200);
  EXPECT_EQ(page, served_viewer_page());
  const auto [script_status, script] = request(server.port(), "/viewer.js?v=1");
  EXPECT_EQ(script_status, 200);
  EXPECT_EQ(script, viewer_script());
  EXPECT_EQ(request(server.port(), "/session.json").second, kSession);
  EXPECT_EQ(request(server.port(), "/etc/passwd").first, 404);
  EXPECT_EQ(request(server.port(), "/", http::verb::post).first, 405);
  EXPECT_EQ(request(server.port(), "/", http::verb::head).first, 200);
  EXPECT_TRUE(eventually([&] { return server.statistics().http_requests == 6u; }))
      << server.statistics().http_requests;
}

TEST(ViewServer, RefusesWebSocketsOpenedByPagesOfOtherSites) {
  auto frames = std::make_shared<FrameBroadcaster>(kFrameSize);
  const ViewServer server(any_port(), kSession, frames);
  const std::string own_origin = "http://127.0.0.1:" + std::to_string(server.port());
  EXPECT_ANY_THROW(testing::FrameClient(server.port(), 0, "http://evil.example"));
  EXPECT_ANY_THROW(testing::FrameClient(server.port(), 0, "null"));
  testing::FrameClient own_page(server.port(), 0, own_origin);
  ASSERT_TRUE(server.wait_for_clients(1, 5000ms));
  frames->publish(frame_of(7));
  const std::vector<double> received = own_page.read_frames(kFrameSize, 1);
  ASSERT_EQ(received.size(), kFrameSize);
  EXPECT_EQ(received[0], 7.0);
}

TEST(ViewServer, RefusesRequestsForAnotherSitesNameOnLoopback) {
  const ViewServer server(any_port(), kSession, nullptr);
  const std::string port = ":" + std::to_string(server.port());
  // A page of evil.example whose name was made to resolve to 127.0.0.1 (DNS rebinding).
  const auto [status, body] =
      request(server.port(), "/session.json", http::verb::get, "evil.example" + port);
  EXPECT_EQ(status, 403);
  EXPECT_NE(body.find("Host header"), std::string::npos) << body;
  EXPECT_EQ(request(server.port(), "/session.json", http::verb::get, "localhost" + port).first,
            200);
}

TEST(ViewServer, StreamsPublishedFramesInOrder) {
  auto frames = std::make_shared<FrameBroadcaster>(kFrameSize);
  const ViewServer server(any_port(), kSession, frames);
  testing::FrameClient client(server.port());
  ASSERT_TRUE(server.wait_for_clients(1, 5000ms));
  for (int i = 0; i < 50; ++i) frames->publish(frame_of(i));
  const std::vector<double> received = client.read_frames(kFrameSize, 50);
  ASSERT_EQ(received.size(), 50 * kFrameSize);
  for (int i = 0; i < 50; ++i) {
    EXPECT_EQ(received[i * kFrameSize], double(i));
    EXPECT_EQ(received[i * kFrameSize + 1], i + 0.25);
  }
  EXPECT_EQ(server.statistics().frames_sent, 50u);
  EXPECT_EQ(server.statistics().frames_skipped, 0u);
}

TEST(ViewServer, ABrowserThatConnectsLateGetsWhatTheRingHolds) {
  auto frames = std::make_shared<FrameBroadcaster>(kFrameSize, 16);
  for (int i = 0; i < 40; ++i) frames->publish(frame_of(i));
  const ViewServer server(any_port(), kSession, frames);
  testing::FrameClient client(server.port());
  const std::vector<double> received = client.read_frames(kFrameSize, 16);
  ASSERT_EQ(received.size(), 16 * kFrameSize);
  EXPECT_EQ(received[0], 24.0);
  EXPECT_EQ(received[15 * kFrameSize], 39.0);
}

TEST(ViewServer, TenBrowsersGetEveryFrame) {
  auto frames = std::make_shared<FrameBroadcaster>(kFrameSize);
  const ViewServer server(any_port(), kSession, frames);
  std::vector<std::unique_ptr<testing::FrameClient>> clients;
  for (int i = 0; i < 10; ++i)
    clients.push_back(std::make_unique<testing::FrameClient>(server.port()));
  ASSERT_TRUE(server.wait_for_clients(10, 5000ms));
  EXPECT_EQ(server.num_clients(), 10u);
  for (int i = 0; i < 100; ++i) frames->publish(frame_of(i));
  for (auto& client : clients) {
    const std::vector<double> received = client->read_frames(kFrameSize, 100);
    ASSERT_EQ(received.size(), 100 * kFrameSize);
    EXPECT_EQ(received[99 * kFrameSize], 99.0);
  }
}

TEST(ViewServer, TheEndMessageFollowsTheLastFrames) {
  auto frames = std::make_shared<FrameBroadcaster>(kFrameSize);
  ViewServer server(any_port(), kSession, frames);
  testing::FrameClient client(server.port());
  ASSERT_TRUE(server.wait_for_clients(1, 5000ms));
  frames->publish(frame_of(7));
  server.end("the rollout is over");
  const std::optional<std::string> first = client.read();
  ASSERT_TRUE(first);
  EXPECT_TRUE(client.binary());
  const std::optional<std::string> last = client.read();
  ASSERT_TRUE(last);
  EXPECT_FALSE(client.binary());
  const nlohmann::json message = nlohmann::json::parse(*last);
  EXPECT_EQ(message["type"], "end");
  EXPECT_EQ(message["reason"], "the rollout is over");
  // Then the server closes the WebSocket and forgets the browser.
  EXPECT_FALSE(client.read());
  EXPECT_TRUE(eventually([&] { return server.num_clients() == 0; }));
}

TEST(ViewServer, AStalledBrowserNeitherBlocksThePublisherNorTheOthers) {
  constexpr std::size_t kBigFrame = kFrameSize * 64;  // 2 kB frames fill a socket quickly
  auto frames = std::make_shared<FrameBroadcaster>(kBigFrame);
  ViewServerConfig config = any_port();
  config.write_timeout = 0.5;
  const ViewServer server(config, kSession, frames);
  testing::FrameClient stalled(server.port(), 4096);  // never reads
  // The other browser reads all along, and remembers the first value of the newest frame.
  std::atomic<bool> stop{false};
  std::atomic<double> newest{0.0};
  std::thread reader([&] {
    testing::FrameClient client(server.port());
    while (!stop.load()) {
      const std::optional<std::string> message = client.read(100ms);
      if (!message || message->size() < kBigFrame * sizeof(double)) continue;
      double first = 0.0;
      std::memcpy(&first, message->data() + message->size() - kBigFrame * sizeof(double),
                  sizeof(double));
      newest.store(first);
    }
  });
  ASSERT_TRUE(server.wait_for_clients(2, 5000ms));
  std::vector<double> frame(kBigFrame, 1.0);
  // The stalled browser's socket fills; the server drops it after write_timeout. Publishing
  // goes on meanwhile (each publish is a copy into the ring).
  const bool dropped = eventually([&] {
    for (int i = 0; i < 200; ++i) frames->publish(frame);
    return server.num_clients() == 1;
  });
  EXPECT_TRUE(dropped) << "the stalled browser was not disconnected";
  frame[0] = -1.0;
  frames->publish(frame);
  EXPECT_TRUE(eventually([&] { return newest.load() == -1.0; }))
      << "the reader got the newest frame";
  EXPECT_EQ(server.num_clients(), 1u) << "the reader was never dropped";
  stop.store(true);
  reader.join();
}

TEST(ViewServer, ABurstBeyondTheRingSkipsTheOldestFramesAndKeepsTheNewest) {
  auto frames = std::make_shared<FrameBroadcaster>(kFrameSize, 16);
  const ViewServer server(any_port(), kSession, frames);
  testing::FrameClient client(server.port());
  ASSERT_TRUE(server.wait_for_clients(1, 5000ms));
  for (int i = 0; i < 1000; ++i) frames->publish(frame_of(i));
  std::vector<double> received;
  while (received.empty() || received[received.size() - kFrameSize] != 999.0) {
    const std::vector<double> more = client.read_frames(kFrameSize, 1);
    ASSERT_FALSE(more.empty());
    received.insert(received.end(), more.begin(), more.end());
  }
  const ViewServerStatistics statistics = server.statistics();
  EXPECT_LT(received.size() / kFrameSize, 1000u);
  EXPECT_EQ(received.size() / kFrameSize + statistics.frames_skipped, 1000u);
  for (std::size_t i = kFrameSize; i < received.size(); i += kFrameSize) {
    EXPECT_GT(received[i], received[i - kFrameSize]) << "frames stay in order";
  }
}

TEST(ViewServer, ForgetsABrowserThatGoesAway) {
  auto frames = std::make_shared<FrameBroadcaster>(kFrameSize);
  const ViewServer server(any_port(), kSession, frames);
  {
    testing::FrameClient client(server.port());
    ASSERT_TRUE(server.wait_for_clients(1, 5000ms));
    client.close_abruptly();
  }
  EXPECT_TRUE(eventually([&] {
    frames->publish(frame_of(1));
    return server.num_clients() == 0;
  }));
  EXPECT_EQ(server.statistics().clients_connected, 1u);
}

TEST(ViewServer, RefusesBrowsersBeyondItsLimit) {
  auto frames = std::make_shared<FrameBroadcaster>(kFrameSize);
  ViewServerConfig config = any_port();
  config.max_clients = 1;
  const ViewServer server(config, kSession, frames);
  testing::FrameClient first(server.port());
  ASSERT_TRUE(server.wait_for_clients(1, 5000ms));
  EXPECT_THROW(testing::FrameClient second(server.port()), beast::system_error);
  EXPECT_EQ(server.num_clients(), 1u);
}

TEST(ViewServer, AReplayServerHasNoFrameStream) {
  const ViewServer server(any_port(), kSession, nullptr);
  EXPECT_THROW(testing::FrameClient client(server.port()), beast::system_error);
}

TEST(ViewServer, NamesABusyPort) {
  const ViewServer first(any_port(), kSession, nullptr);
  ViewServerConfig config;
  config.port = first.port();
  try {
    const ViewServer second(config, kSession, nullptr);
    FAIL() << "two servers on one port";
  } catch (const ViewError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("127.0.0.1:" + std::to_string(first.port())), std::string::npos);
    EXPECT_NE(message.find("in use"), std::string::npos) << message;
  }
  // The first one still serves.
  EXPECT_EQ(request(first.port(), "/session.json").first, 200);
}

TEST(ViewServer, NamesBadSettings) {
  ViewServerConfig config = any_port();
  config.host = "localhost.invalid";
  EXPECT_THROW(ViewServer(config, kSession, nullptr), ViewError);
  config = any_port();
  config.port = 70000;
  EXPECT_THROW(ViewServer(config, kSession, nullptr), ViewError);
  config = any_port();
  config.send_period = 0.0;
  EXPECT_THROW(ViewServer(config, kSession, nullptr), ViewError);
}

TEST(ViewServer, MalformedRequestsCloseTheirConnectionOnly) {
  const ViewServer server(any_port(), kSession, nullptr);
  net::io_context io;
  tcp::socket socket(io);
  socket.connect(tcp::endpoint(net::ip::make_address("127.0.0.1"),
                               static_cast<unsigned short>(server.port())));
  const std::string garbage = "NOT HTTP AT ALL\r\n\x01\x02\r\n\r\n";
  net::write(socket, net::buffer(garbage));
  std::array<char, 64> reply{};
  beast::error_code error;
  socket.read_some(net::buffer(reply), error);
  EXPECT_TRUE(error) << "the server closes the connection";
  EXPECT_EQ(request(server.port(), "/session.json").first, 200);
}

}  // namespace
}  // namespace upkie_rl
