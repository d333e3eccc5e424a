#include "view/view_server_monitor.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace upkie_rl {
namespace {

using namespace std::chrono_literals;

TEST(ViewServerMonitor, CountsWhatTheServerReports) {
  ViewServerMonitor monitor;
  monitor.client_opened(1);
  monitor.client_opened(2);
  monitor.client_closed(1);
  monitor.http_request();
  monitor.frames_collected(3, 2);
  monitor.frames_collected(0, 5);  // nothing to send: no message, frames still skipped
  const ViewServerStatistics statistics = monitor.statistics();
  EXPECT_EQ(monitor.num_clients(), 1u);
  EXPECT_EQ(statistics.clients_connected, 2u);
  EXPECT_EQ(statistics.http_requests, 1u);
  EXPECT_EQ(statistics.messages_sent, 1u);
  EXPECT_EQ(statistics.frames_sent, 3u);
  EXPECT_EQ(statistics.frames_skipped, 7u);
}

TEST(ViewServerMonitor, WaitsForClientsUntilTheyComeOrTheTimeout) {
  ViewServerMonitor monitor;
  EXPECT_FALSE(monitor.wait_for_clients(1, 20ms, nullptr));
  std::thread server([&monitor] {
    std::this_thread::sleep_for(20ms);
    monitor.client_opened(1);
  });
  EXPECT_TRUE(monitor.wait_for_clients(1, 5000ms, nullptr));
  server.join();
  const std::atomic<bool> interrupted{true};
  EXPECT_FALSE(monitor.wait_for_clients(2, 5000ms, &interrupted));
}

TEST(ViewServerMonitor, TheEndIsWaitedForUntilEveryBrowserOfItsAudienceHasIt) {
  ViewServerMonitor monitor;
  const auto started = std::chrono::steady_clock::now();
  monitor.wait_for_end(30ms);  // not posted: waits the whole timeout
  EXPECT_GE(std::chrono::steady_clock::now() - started, 30ms);
  monitor.end_posted(2);
  std::thread server([&monitor] {
    monitor.end_delivered();
    std::this_thread::sleep_for(10ms);
    monitor.end_delivered();
  });
  const auto waited_from = std::chrono::steady_clock::now();
  monitor.wait_for_end(10000ms);
  EXPECT_LT(std::chrono::steady_clock::now() - waited_from, 5000ms);
  server.join();
}

}  // namespace
}  // namespace upkie_rl
