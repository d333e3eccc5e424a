// `upkie-rl spine` as a process: our agent against it, compared with the same Bullet
// simulation in process; clean exits on signals and on bad messages.

#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "model/robot_model.hpp"
#include "sim/bullet_simulation.hpp"
#include "spine/spine_backend.hpp"
#include "spine/spine_error.hpp"

extern char** environ;

namespace upkie_rl {
namespace {

std::string unique_name(const std::string& tag) {
  static int counter = 0;
  return "/upkie_rl_cli_" + tag + "_" + std::to_string(::getpid()) + "_" +
         std::to_string(counter++);
}

/// `upkie-rl spine ...` in a child process; SIGKILLed at destruction if still running.
class SpineProcess {
 public:
  explicit SpineProcess(std::vector<std::string> args) {
    args.insert(args.begin(), {UPKIE_RL_CLI_PATH, "spine"});
    std::vector<char*> argv;
    for (std::string& arg : args) argv.push_back(arg.data());
    argv.push_back(nullptr);
    if (::posix_spawn(&pid_, UPKIE_RL_CLI_PATH, nullptr, nullptr, argv.data(), environ) != 0) {
      pid_ = -1;
    }
  }
  ~SpineProcess() {
    if (pid_ > 0 && !exited_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  bool started() const { return pid_ > 0; }

  /// Waits for the shared memory to appear (the spine is serving).
  bool wait_for(const std::string& shm_name) {
    for (int i = 0; i < 3000; ++i) {
      if (std::filesystem::exists("/dev/shm" + shm_name)) return true;
      if (exit_code(false) >= 0) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }

  /// Exit code once exited (-1 if still running and !block; 128+n if killed by signal n).
  int exit_code(bool block = true) {
    if (exited_) return status_;
    int status = 0;
    const pid_t result = ::waitpid(pid_, &status, block ? 0 : WNOHANG);
    if (result != pid_) return -1;
    exited_ = true;
    status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return status_;
  }

  void signal(int signal) { ::kill(pid_, signal); }

 private:
  pid_t pid_ = -1;
  bool exited_ = false;
  int status_ = -1;
};

/// Legs held straight, wheels at a velocity that varies with time.
ServoAction test_action(int step) {
  ServoAction action;
  for (std::size_t i = 0; i < kNumServos; ++i) {
    action[i].position = is_wheel(i) ? std::nan("") : 0.0;
    action[i].velocity = is_wheel(i) ? (i == kLeftWheel ? 1.0 : -1.0) * std::sin(0.05 * step) : 0.0;
    action[i].maximum_torque = is_wheel(i) ? 1.7 : 16.0;
  }
  return action;
}

TEST(SpineCommand, OnRequestSpineMatchesInProcessBullet) {
  const std::string name = unique_name("match");
  SpineProcess spine({"--shm-name", name, "--nb-substeps", "5"});
  ASSERT_TRUE(spine.started());
  ASSERT_TRUE(spine.wait_for(name));

  SpineBackendConfig config;
  config.shm_name = name;
  config.regulate_frequency = false;
  config.request_timeout = 5.0;  // a loaded test machine may stall the spine process
  SpineBackend backend(config);
  BulletSimulation local(RobotModel::default_model());  // 1 ms steps, 5 per agent step

  ResetState state;
  state.orientation_base_in_world =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitY()));
  state.joint_configuration = {0.1, -0.2, 0.0, -0.1, 0.2, 0.0};
  const Observation remote_first = backend.reset(state);
  const Observation& local_first = local.reset(state);
  EXPECT_EQ(remote_first.sim_base.position, local_first.sim_base.position);

  // Largest difference of joint positions, torques, pitch and base position between two
  // simulations over `nb_steps` steps of the same commands.
  const auto max_difference_over = [](Simulation& first, Simulation& second, int nb_steps) {
    double max_difference = 0.0;
    for (int step = 0; step < nb_steps; ++step) {
      const Observation& a = first.step(test_action(step));
      const Observation& b = second.step(test_action(step));
      EXPECT_NEAR(a.time, b.time, 1e-12);
      for (std::size_t i = 0; i < kNumServos; ++i) {
        max_difference =
            std::max(max_difference, std::abs(a.servo[i].position - b.servo[i].position));
        max_difference = std::max(max_difference, std::abs(a.servo[i].torque - b.servo[i].torque));
      }
      max_difference =
          std::max(max_difference, std::abs(a.base_orientation.pitch - b.base_orientation.pitch));
      max_difference = std::max(max_difference, (a.sim_base.position - b.sim_base.position).norm());
    }
    return max_difference;
  };
  // Same code, same commands, float64 on the wire: the trajectories are identical.
  EXPECT_EQ(max_difference_over(backend, local, 200), 0.0);

  // The servo gains of the Start configuration reach the spine's simulation.
  SpineBackendConfig soft_config = config;
  soft_config.start_parameters.kp = 12.0;
  soft_config.start_parameters.kd = 0.6;
  SpineBackend soft_backend(soft_config);
  BulletConfig soft_bullet;
  soft_bullet.servo_gains.kp = 12.0;
  soft_bullet.servo_gains.kd = 0.6;
  BulletSimulation soft_local(RobotModel::default_model(), soft_bullet);
  soft_backend.reset(state);
  soft_local.reset(state);
  EXPECT_EQ(max_difference_over(soft_backend, soft_local, 100), 0.0);
  soft_local.reset(state);
  local.reset(state);
  EXPECT_GT(max_difference_over(soft_local, local, 100), 1e-3);  // the gains matter

  spine.signal(SIGTERM);
  EXPECT_EQ(spine.exit_code(), 0);
  EXPECT_FALSE(std::filesystem::exists("/dev/shm" + name));
}

TEST(SpineCommand, BadMessageShutsTheSpineDownAndCleansUp) {
  const std::string name = unique_name("bad");
  SpineProcess spine({"--shm-name", name, "--nb-substeps", "5"});
  ASSERT_TRUE(spine.wait_for(name));
  {
    SharedMemory memory = SharedMemory::open(name);
    const std::string nil_message("\x81\xa5servo\xc0", 8);  // {"servo": nil}
    memory.write_payload({nil_message.data(), nil_message.size()});
    memory.set_request(Request::kStart);  // after the stop cycles: Reset on this payload
  }
  EXPECT_EQ(spine.exit_code(), 1);
  EXPECT_FALSE(std::filesystem::exists("/dev/shm" + name));
}

TEST(SpineCommand, RealTimeSpineStopsOnSigint) {
  const std::string name = unique_name("rt");
  SpineProcess spine({"--shm-name", name});
  ASSERT_TRUE(spine.wait_for(name));
  SpineBackendConfig config;
  config.shm_name = name;
  config.request_timeout = 1.0;
  SpineBackend backend(config);
  const double start_time = backend.reset(ResetState{}).time;
  double time = start_time;
  for (int step = 0; step < 40; ++step) time = backend.step(test_action(step)).time;
  EXPECT_GT(time, start_time);  // the spine simulated in real time in between
  spine.signal(SIGINT);
  EXPECT_EQ(spine.exit_code(), 0);
  EXPECT_FALSE(std::filesystem::exists("/dev/shm" + name));
  EXPECT_THROW(backend.step(test_action(0)), SpineError);  // gone: times out cleanly
}

TEST(SpineCommand, RejectsBadOptions) {
  SpineProcess spine({"--spine-frequency", "0"});
  EXPECT_NE(spine.exit_code(), 0);
  SpineProcess bad_name({"--shm-name", "no-slash", "--nb-substeps", "5"});
  EXPECT_EQ(bad_name.exit_code(), 1);
}

}  // namespace
}  // namespace upkie_rl
