// `upkie-rl rollout` through the spine gives the same result as in-process simulation, on
// Bullet and on MuJoCo.
//
// Tolerance: the on-request spine runs the same BulletSimulation code with the same
// physics settings (1 ms steps, 5 per 200 Hz agent step), resets rebuild the Bullet world
// in both, and every number crosses the link as msgpack float64, which is lossless. So
// the trajectories are expected to be bit-identical; the test allows 1e-9 relative on the
// returns only so that a future change of the link's float printing or of summation
// order in the report does not make it flaky, which is far below any physical effect
// (one 1 ms step of difference changes the return by ~1e-3).

#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace {

/// Runs a shell command, returns its standard output.
std::string run(const std::string& command, int& exit_code) {
  std::string output;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) {
    exit_code = -1;
    return output;
  }
  std::array<char, 4096> chunk{};
  while (std::fgets(chunk.data(), chunk.size(), pipe) != nullptr) output += chunk.data();
  const int status = ::pclose(pipe);
  exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return output;
}

nlohmann::json last_line_json(const std::string& output) {
  const auto end = output.find_last_not_of('\n');
  const auto start = output.rfind('\n', end);
  return nlohmann::json::parse(output.substr(start == std::string::npos ? 0 : start + 1));
}

/// Rolls the PD law out on `env_id` in process and on `upkie-rl spine --backend backend`.
void expect_same_returns_through_the_spine(const std::string& backend, const std::string& env_id) {
  const std::string cli = UPKIE_RL_CLI_PATH;
  const std::string shm_name = "/upkie_rl_rollout_" + backend + std::to_string(::getpid());
  std::vector<std::string> args = {cli, "spine",     "--shm-name", shm_name, "--nb-substeps",
                                   "5", "--backend", backend};
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  pid_t spine = -1;
  ASSERT_EQ(::posix_spawn(&spine, cli.c_str(), nullptr, nullptr, argv.data(), environ), 0);
  for (int i = 0; i < 3000 && !std::filesystem::exists("/dev/shm" + shm_name); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }

  const std::string common =
      " --controller linear:10,1,0,0.1 --episodes 2 --max-steps 300 --seed 3 --json";
  int bullet_exit = -1;
  const std::string bullet = run(cli + " rollout --env " + env_id + common, bullet_exit);
  int spine_exit = -1;
  const std::string through_spine =
      run(cli + " rollout --env Upkie-Spine-Pendulum --env-option shm_name=" + shm_name +
              " --env-option regulate_frequency=false --env-option request_timeout=5" + common,
          spine_exit);

  ::kill(spine, SIGINT);
  int status = 0;
  ::waitpid(spine, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_FALSE(std::filesystem::exists("/dev/shm" + shm_name));

  ASSERT_EQ(bullet_exit, 0) << bullet;
  ASSERT_EQ(spine_exit, 0) << through_spine;
  const auto expected = last_line_json(bullet);
  const auto actual = last_line_json(through_spine);
  ASSERT_EQ(expected["returns"].size(), 2u);
  ASSERT_EQ(actual["returns"].size(), 2u);
  for (std::size_t e = 0; e < 2; ++e) {
    const double reference = expected["returns"][e].get<double>();
    EXPECT_NEAR(actual["returns"][e].get<double>(), reference, 1e-9 * std::abs(reference))
        << "episode " << e;
    EXPECT_EQ(actual["lengths"][e], expected["lengths"][e]);
  }
  EXPECT_EQ(expected["lengths"][0].get<int>(), 300);  // the law balances: full episodes
}

TEST(SpineRollout, SameReturnsThroughTheSpineAsInProcess) {
  expect_same_returns_through_the_spine("bullet", "Upkie-Bullet-Pendulum");
}

TEST(SpineRollout, SameReturnsThroughAMujocoSpine) {
  expect_same_returns_through_the_spine("mujoco", "Upkie-MuJoCo-Pendulum");
}

}  // namespace
