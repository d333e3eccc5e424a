#pragma once
// What the runner's tests share: a real-time `upkie-rl spine` on its own shared memory, the
// runner started against it, and the test policies.

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "common/background_process.hpp"

namespace upkie_rl::testing {

inline const std::string kPolicies = std::string(UPKIE_RL_TEST_DATA_DIR) + "/policies/";
inline const std::string kPendulum = kPolicies + "pendulum_bullet_seed0.ckpt";
inline const std::string kServosBalance = kPolicies + "servos_balance_mujoco_seed0.ckpt";
inline const std::string kVelocity = kPolicies + "velocity_mujoco_seed0.ckpt";
/// The spine protocol's Stop request word.
constexpr std::uint32_t kStopRequest = 3;

/// A real-time `upkie-rl spine` on its own shared memory, removed at the end.
class Spine {
 public:
  explicit Spine(const std::string& tag, std::vector<std::string> extra = {},
                 const std::string& backend = "bullet")
      : shm_name_("/upkie_rl_agent_" + tag + std::to_string(::getpid())),
        process_(arguments(shm_name_, backend, std::move(extra)), "agent_spine_" + tag) {
    for (int i = 0; i < 3000 && !std::filesystem::exists(path()); ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  ~Spine() {
    process_.wait(SIGINT);
    std::filesystem::remove(path());  // left by a killed spine
  }
  Spine(const Spine&) = delete;
  Spine& operator=(const Spine&) = delete;

  const std::string& shm_name() const { return shm_name_; }
  std::filesystem::path path() const { return "/dev/shm" + shm_name_; }
  BackgroundProcess& process() { return process_; }

  /// The request word of the shared memory.
  std::uint32_t request() const {
    std::ifstream in(path(), std::ios::binary);
    std::uint32_t word = 0;
    in.read(reinterpret_cast<char*>(&word), sizeof(word));
    return word;
  }

 private:
  static std::vector<std::string> arguments(const std::string& shm_name, const std::string& backend,
                                            std::vector<std::string> extra) {
    std::vector<std::string> args = {UPKIE_RL_CLI_PATH, "spine",     "--shm-name",
                                     shm_name,          "--backend", backend};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }

  std::string shm_name_;
  BackgroundProcess process_;
};

/// upkie-rl-agent with `model` on `spine`, in the background.
inline std::unique_ptr<BackgroundProcess> start_agent(const Spine& spine, const std::string& model,
                                                      const std::string& tag,
                                                      std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {UPKIE_RL_AGENT_PATH, "--model", model, "--shm-name",
                                   spine.shm_name()};
  args.insert(args.end(), extra.begin(), extra.end());
  return std::make_unique<BackgroundProcess>(args, "agent_" + tag);
}

/// Waits until the agent's log says it is running (at most 20 s).
inline bool wait_running(const BackgroundProcess& agent) {
  for (int i = 0; i < 2000; ++i) {
    if (agent.output().find("starting -> running") != std::string::npos) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

/// The log of a run the supervisor stopped: stopping, stop commands, stopped, summary.
inline void expect_supervised_stop(const std::string& output, const std::string& reason) {
  EXPECT_NE(output.find("-> stopping: " + reason), std::string::npos) << output;
  EXPECT_NE(output.find("Stop request"), std::string::npos) << output;
  EXPECT_NE(output.find("stopping -> stopped: detached"), std::string::npos) << output;
  EXPECT_NE(output.find("summary: "), std::string::npos) << output;
}

}  // namespace upkie_rl::testing
