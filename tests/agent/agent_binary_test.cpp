// upkie-rl-agent links none of what the robot must not carry: libtorch, Bullet, MuJoCo, EGL
// (shared libraries, from ldd) and Boost.Beast (header-only: no symbol of it in the binary).

#include <gtest/gtest.h>

#include "common/shell_output.hpp"

#include <array>
#include <cstdio>
#include <string>

namespace upkie_rl {
namespace {

TEST(AgentBinary, LinksNoEngineTorchEglOrHttpServer) {
  const std::string agent = UPKIE_RL_AGENT_PATH;
  const std::string libraries = testing::shell_output("ldd " + agent);
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
