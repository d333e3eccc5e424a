/// A rank of `upkie-rl train` that cannot meet the others ends with at most three lines of
/// its own naming the cause: none of libtorch's c10d log lines (one per retry, about 300
/// for an unresolvable MASTER_ADDR with the default --dist-timeout).

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <string>
#include <vector>

#include "common/background_process.hpp"
#include "common/temp_files.hpp"

namespace upkie_rl {
namespace {

using Process = testing::BackgroundProcess;

/// `upkie-rl train` arguments of a short pendulum run that waits `timeout` s for the others.
std::vector<std::string> rank_args(const std::string& timeout) {
  return {UPKIE_RL_CLI_PATH,
          "train",
          "--config",
          std::string(UPKIE_RL_SOURCE_DIR) + "/configs/pendulum.yaml",
          "--set",
          "ppo.total_timesteps=128",
          "--set",
          "ppo.n_steps=64",
          "--set",
          "ppo.batch_size=32",
          "--set",
          "env.num_envs=2",
          "--quiet",
          "--run-dir",
          testing::temp_path("rendezvous_message_run").string(),
          "--dist-timeout",
          timeout};
}

std::vector<std::string> launch_variables(int rank, const std::string& address, int port) {
  return {"WORLD_SIZE=2", "RANK=" + std::to_string(rank), "MASTER_ADDR=" + address,
          "MASTER_PORT=" + std::to_string(port)};
}

std::size_t line_count(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

/// Runs the rank to its end; checks it failed in at most three lines, none of libtorch's,
/// that contain `cause`.
void expect_short_failure(Process& rank, const std::string& cause) {
  EXPECT_NE(rank.wait(), 0);
  const std::string output = rank.output();
  EXPECT_LE(line_count(output), 3U) << output;
  EXPECT_EQ(output.find("[c10d]"), std::string::npos) << output;
  EXPECT_NE(output.find(cause), std::string::npos) << output;
}

TEST(RendezvousMessage, APortTakenByAnotherProgramIsShort) {
  // Another program listening on every interface at the port rank 0 must serve on.
  const int other = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_ANY);
  ASSERT_EQ(::bind(other, reinterpret_cast<sockaddr*>(&address), sizeof(address)), 0);
  ASSERT_EQ(::listen(other, 1), 0);
  socklen_t length = sizeof(address);
  ::getsockname(other, reinterpret_cast<sockaddr*>(&address), &length);
  const int port = ntohs(address.sin_port);
  Process rank0(rank_args("3"), "rendezvous_port_taken", launch_variables(0, "127.0.0.1", port));
  expect_short_failure(rank0, std::to_string(port));
  ::close(other);
}

TEST(RendezvousMessage, AnUnresolvableMasterAddressIsNamed) {
  Process rank0(rank_args("2"), "rendezvous_bad_host",
                launch_variables(0, "no.such.host.invalid", testing::free_port()));
  expect_short_failure(rank0, "MASTER_ADDR \"no.such.host.invalid\" does not resolve");
}

TEST(RendezvousMessage, NoRankZeroIsShort) {
  const int port = testing::free_port();
  Process rank1(rank_args("2"), "rendezvous_no_server", launch_variables(1, "127.0.0.1", port));
  expect_short_failure(rank1, "127.0.0.1:" + std::to_string(port));
}

}  // namespace
}  // namespace upkie_rl
