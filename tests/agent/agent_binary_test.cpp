// upkie-rl-agent links none of what the robot must not carry: libtorch, Bullet, MuJoCo, EGL
// (shared libraries, from ldd) and Boost.Beast (header-only: no symbol of it in the binary).

#include <gtest/gtest.h>

#include "common/shell_output.hpp"

#include <array>
#include <cstdio>
#include <sstream>
#include <string>

namespace upkie_rl {
namespace {

/// ldd's lines without their load addresses: "(0x00007f83595c1000)" holds "c10" one run in
/// about thirty (address space layout randomisation), which is not libtorch's c10.
std::string without_load_addresses(const std::string& ldd_output) {
  std::istringstream lines(ldd_output);
  std::string names;
  for (std::string line; std::getline(lines, line);) {
    names += line.substr(0, line.find(" (0x")) + "\n";
  }
  return names;
}

TEST(AgentBinaryHelpers, LoadAddressesAreLeftOut) {
  const std::string names = without_load_addresses(
      "\tlibfmt.so.10 => /lib/x86_64-linux-gnu/libfmt.so.10 (0x00007f83595c1000)\n"
      "\t/lib64/ld-linux-x86-64.so.2 (0x00007f83598ca000)\n");
  EXPECT_EQ(
      names,
      "\tlibfmt.so.10 => /lib/x86_64-linux-gnu/libfmt.so.10\n\t/lib64/ld-linux-x86-64.so.2\n");
  EXPECT_EQ(names.find("c10"), std::string::npos);
}

TEST(AgentBinary, LinksNoEngineTorchEglOrHttpServer) {
  const std::string agent = UPKIE_RL_AGENT_PATH;
  const std::string libraries = without_load_addresses(testing::shell_output("ldd " + agent));
  ASSERT_NE(libraries.find("libc.so"), std::string::npos) << libraries;
  for (const char* forbidden :
       {"torch", "c10", "Bullet", "mujoco", "libEGL", "libGL", "gloo", "boost", "python"}) {
    EXPECT_EQ(libraries.find(forbidden), std::string::npos) << forbidden << " in\n" << libraries;
  }
  const std::string symbols =
      testing::shell_output("nm -C " + agent + " | grep -c -i -E 'beast|asio'");
  EXPECT_EQ(std::stoi(symbols), 0) << "Boost.Beast or Asio symbols in " << agent;
  // The same check on upkie-rl finds them, so the test can fail.
  const std::string cli_libraries = testing::shell_output(std::string("ldd ") + UPKIE_RL_CLI_PATH);
  EXPECT_NE(cli_libraries.find("torch"), std::string::npos) << cli_libraries;
}

}  // namespace
}  // namespace upkie_rl
