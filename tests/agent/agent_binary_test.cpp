// upkie-rl-agent links none of what the robot must not carry: libtorch, Bullet, MuJoCo, EGL
// (shared libraries, from ldd) and Boost.Beast (header-only: no symbol of it in the binary).

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <string>

namespace {

std::string command_output(const std::string& command) {
  std::string output;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return output;
  std::array<char, 4096> chunk{};
  while (std::fgets(chunk.data(), chunk.size(), pipe) != nullptr) output += chunk.data();
  ::pclose(pipe);
  return output;
}

TEST(AgentBinary, LinksNoEngineTorchEglOrHttpServer) {
  const std::string agent = UPKIE_RL_AGENT_PATH;
  const std::string libraries = command_output("ldd " + agent);
  ASSERT_NE(libraries.find("libc.so"), std::string::npos) << libraries;
  for (const char* forbidden :
       {"torch", "c10", "Bullet", "mujoco", "libEGL", "libGL", "gloo", "boost", "python"}) {
    EXPECT_EQ(libraries.find(forbidden), std::string::npos) << forbidden << " in\n" << libraries;
  }
  const std::string symbols = command_output("nm -C " + agent + " | grep -c -i -E 'beast|asio'");
  EXPECT_EQ(std::stoi(symbols), 0) << "Boost.Beast or Asio symbols in " << agent;
  // The same check on upkie-rl finds them, so the test can fail.
  const std::string cli_libraries = command_output(std::string("ldd ") + UPKIE_RL_CLI_PATH);
  EXPECT_NE(cli_libraries.find("torch"), std::string::npos) << cli_libraries;
}

}  // namespace
