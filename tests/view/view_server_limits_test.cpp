// Fault injection (issue 26, item 5): idle connections cannot exhaust the process's
// descriptors, the server recovers from running out of them, and it does not spin when idle.

#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <ctime>
#include <limits>
#include <thread>
#include <vector>

#include "view/view_error.hpp"
#include "view/view_server.hpp"

namespace upkie_rl {
namespace {

using namespace std::chrono_literals;

/// A plain TCP connection to 127.0.0.1:`port` that sends nothing (-1 on failure).
int idle_connection(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

/// Whether the server answers a GET / with 200 on a fresh connection.
bool answers(int port) {
  const int fd = idle_connection(port);
  if (fd < 0) return false;
  const timeval timeout{2, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
  const std::string get = "GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n";
  ::send(fd, get.data(), get.size(), MSG_NOSIGNAL);
  char reply[32] = {};
  const ssize_t read = ::recv(fd, reply, sizeof(reply) - 1, 0);
  ::close(fd);
  return read > 12 && std::string(reply, 12) == "HTTP/1.1 200";
}

/// Whether the server closed `fd` (a read returns 0 or an error at once).
bool closed_by_server(int fd) {
  const timeval timeout{1, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
  char byte = 0;
  return ::recv(fd, &byte, 1, 0) == 0;
}

std::shared_ptr<const FrameBroadcaster> frames() { return std::make_shared<FrameBroadcaster>(4); }

TEST(ViewServerLimits, ConnectionsBeyondTheCapAreClosedAtOnceAndIdleOnesTimeOut) {
  ViewServerConfig config;
  config.port = 0;
  config.max_connections = 4;
  config.idle_timeout = 1.0;
  ViewServer server(config, "{}", frames());
  std::vector<int> idle;
  for (int i = 0; i < 4; ++i) idle.push_back(idle_connection(server.port()));
  std::this_thread::sleep_for(200ms);
  const int over = idle_connection(server.port());
  ASSERT_GE(over, 0);
  EXPECT_TRUE(closed_by_server(over));
  ::close(over);
  // The four idle ones are closed after the idle timeout; then the server answers again.
  std::this_thread::sleep_for(1500ms);
  for (int fd : idle) {
    EXPECT_TRUE(closed_by_server(fd));
    ::close(fd);
  }
  EXPECT_TRUE(answers(server.port()));
}

TEST(ViewServerLimits, RunningOutOfDescriptorsIsSurvivedAndDoesNotSpin) {
  ViewServerConfig config;
  config.port = 0;
  ViewServer server(config, "{}", frames());
  testing::internal::CaptureStderr();  // its file is opened while descriptors remain
  rlimit original{};
  ASSERT_EQ(::getrlimit(RLIMIT_NOFILE, &original), 0);
  rlimit lowered = original;
  lowered.rlim_cur = std::min<rlim_t>(original.rlim_cur, 512);
  ASSERT_EQ(::setrlimit(RLIMIT_NOFILE, &lowered), 0);
  // Use up the descriptors: the server's accept fails with EMFILE.
  std::vector<int> hog;
  for (int fd = ::dup(0); fd >= 0; fd = ::dup(0)) hog.push_back(fd);
  const int pending = [&] {
    ::close(hog.back());  // one descriptor for the client socket
    hog.pop_back();
    return idle_connection(server.port());
  }();
  ASSERT_GE(pending, 0);
  const std::clock_t cpu_before = std::clock();
  std::this_thread::sleep_for(1s);
  const double cpu_seconds = static_cast<double>(std::clock() - cpu_before) / CLOCKS_PER_SEC;
  EXPECT_LT(cpu_seconds, 0.3) << "the server spun while out of descriptors";
  for (int fd : hog) ::close(fd);
  ::close(pending);
  ASSERT_EQ(::setrlimit(RLIMIT_NOFILE, &original), 0);
  std::this_thread::sleep_for(500ms);
  EXPECT_TRUE(answers(server.port()));
  // Said once for the spell of failures, in one whole line (and, under UBSan, without the
  // false report its vptr check made on a stream call while descriptors were out).
  EXPECT_EQ(testing::internal::GetCapturedStderr(),
            "viewer: cannot accept connections (Too many open files); retrying every 200 ms\n");
}

TEST(ViewServerLimits, IdleServerDoesNotWakeUp) {
  ViewServerConfig config;
  config.port = 0;
  ViewServer server(config, "{}", frames());
  const std::clock_t cpu_before = std::clock();
  std::this_thread::sleep_for(1s);
  EXPECT_LT(static_cast<double>(std::clock() - cpu_before) / CLOCKS_PER_SEC, 0.05);
  EXPECT_TRUE(answers(server.port()));
}

TEST(ViewServerLimits, ConfigurationIsChecked) {
  ViewServerConfig config;
  config.max_connections = 0;
  EXPECT_THROW(config.validate(), ViewError);
  config.max_connections = 8;
  config.idle_timeout = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(config.validate(), ViewError);
}

}  // namespace
}  // namespace upkie_rl
