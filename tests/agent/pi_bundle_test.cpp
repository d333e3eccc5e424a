// The robot's bundle (make pi): an aarch64 upkie-rl-agent that needs no library beyond the C
// library and its own lib/, and that, run by qemu-aarch64 against the native
// `upkie-rl spine` through shared memory, balances the pendulum policy 10 s.

#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

#include "common/background_process.hpp"
#include "common/shell_output.hpp"

namespace upkie_rl {
namespace {

#ifdef UPKIE_RL_PI_BUNDLE
const std::filesystem::path kBundle = UPKIE_RL_PI_BUNDLE;

TEST(PiBundle, HoldsAnAarch64RunnerAndEverythingItNeeds) {
  for (const char* file : {"upkie-rl-agent", "policy.ckpt", "upkie.urdf", "run-agent.sh",
                           "README.md", "lib/libstdc++.so.6"}) {
    EXPECT_TRUE(std::filesystem::exists(kBundle / file)) << file;
  }
  // yaml-cpp's soname: libyaml-cpp.so.0.7 on Debian 12, .0.8 on Debian 13.
  bool has_yaml_cpp = false;
  for (const auto& entry : std::filesystem::directory_iterator(kBundle / "lib")) {
    has_yaml_cpp |= entry.path().filename().string().starts_with("libyaml-cpp.so.0.");
  }
  EXPECT_TRUE(has_yaml_cpp) << "no lib/libyaml-cpp.so.0.* in " << kBundle;
  const std::string header =
      testing::shell_output("readelf -h " + (kBundle / "upkie-rl-agent").string());
  EXPECT_NE(header.find("AArch64"), std::string::npos) << header;
  const std::string dynamic =
      testing::shell_output("readelf -d " + (kBundle / "upkie-rl-agent").string());
  EXPECT_NE(dynamic.find("[$ORIGIN/lib]"), std::string::npos) << dynamic;
  for (const char* forbidden : {"torch", "Bullet", "mujoco", "EGL", "boost", "spdlog", "fmt"}) {
    EXPECT_EQ(dynamic.find(forbidden), std::string::npos) << forbidden << " in\n" << dynamic;
  }
}

TEST(PiBundle, BalancesThePendulumUnderQemuAgainstTheNativeSpine) {
  const std::string shm_name = "/upkie_rl_agent_qemu" + std::to_string(::getpid());
  testing::BackgroundProcess spine({UPKIE_RL_CLI_PATH, "spine", "--shm-name", shm_name},
                                   "qemu_spine");
  for (int i = 0; i < 3000 && !std::filesystem::exists("/dev/shm" + shm_name); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  testing::BackgroundProcess agent(
      {"qemu-aarch64", "-L", "/usr/aarch64-linux-gnu", (kBundle / "upkie-rl-agent").string(),
       "--model", (kBundle / "policy.ckpt").string(), "--shm-name", shm_name, "--duration", "10"},
      "qemu_agent", {"UPKIE_RL_MODEL=" + (kBundle / "upkie.urdf").string()});
  const int status = agent.wait();
  spine.wait(SIGINT);
  const std::string output = agent.output();
  EXPECT_EQ(status, 0) << output;
  EXPECT_NE(output.find("running -> stopping: duration of 10 s reached"), std::string::npos)
      << output;
  EXPECT_NE(output.find("5 of 5 stop cycles answered"), std::string::npos) << output;
  const auto at = output.find("summary: ");
  ASSERT_NE(at, std::string::npos) << output;
  EXPECT_GT(std::stol(output.substr(at + 9)), 1500) << output;
}
#else
TEST(PiBundle, NotBuilt) {
  GTEST_SKIP() << "no aarch64 cross compiler at configuration: install-deps.sh installs it";
}
#endif

}  // namespace
}  // namespace upkie_rl
