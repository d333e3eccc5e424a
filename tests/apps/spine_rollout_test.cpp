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

#include "common/velocity_baseline.hpp"

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

/// A rollout of the same controller in process and through `upkie-rl spine`.
struct SpineComparison {
  std::string backend;  ///< The spine's engine.
  std::string env_id;   ///< In process.
  std::string spine_env_id;
  int nb_substeps = 5;  ///< Physics steps per agent step, both sides.
  std::string controller = "linear:10,1,0,0.1";
  int max_steps = 300;
  /// A world the spine plays hidden from its agent ...
  std::vector<std::string> spine_world;
  /// ... and the same world told to the in-process environment (" --env-option ...").
  std::string env_options;
};

/// Runs `comparison` and expects the same returns and lengths on both sides.
void expect_same_returns_through_the_spine(const SpineComparison& comparison) {
  const std::string cli = UPKIE_RL_CLI_PATH;
  const std::string shm_name =
      "/upkie_rl_rollout_" + comparison.backend + std::to_string(::getpid());
  std::vector<std::string> args = {
      cli,         "spine",           "--shm-name",
      shm_name,    "--nb-substeps",   std::to_string(comparison.nb_substeps),
      "--backend", comparison.backend};
  args.insert(args.end(), comparison.spine_world.begin(), comparison.spine_world.end());
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  pid_t spine = -1;
  ASSERT_EQ(::posix_spawn(&spine, cli.c_str(), nullptr, nullptr, argv.data(), environ), 0);
  for (int i = 0; i < 3000 && !std::filesystem::exists("/dev/shm" + shm_name); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }

  const std::string common = " --controller " + comparison.controller +
                             " --episodes 2 --max-steps " + std::to_string(comparison.max_steps) +
                             " --seed 3 --json";
  int in_process_exit = -1;
  const std::string in_process =
      run(cli + " rollout --env " + comparison.env_id + comparison.env_options + common,
          in_process_exit);
  int spine_exit = -1;
  const std::string through_spine =
      run(cli + " rollout --env " + comparison.spine_env_id + " --env-option shm_name=" + shm_name +
              " --env-option regulate_frequency=false --env-option request_timeout=5" + common,
          spine_exit);

  ::kill(spine, SIGINT);
  int status = 0;
  ::waitpid(spine, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_FALSE(std::filesystem::exists("/dev/shm" + shm_name));

  ASSERT_EQ(in_process_exit, 0) << in_process;
  ASSERT_EQ(spine_exit, 0) << through_spine;
  const auto expected = last_line_json(in_process);
  const auto actual = last_line_json(through_spine);
  ASSERT_EQ(expected["returns"].size(), 2u);
  ASSERT_EQ(actual["returns"].size(), 2u);
  for (std::size_t e = 0; e < 2; ++e) {
    const double reference = expected["returns"][e].get<double>();
    EXPECT_NEAR(actual["returns"][e].get<double>(), reference, 1e-9 * std::abs(reference))
        << "episode " << e;
    EXPECT_EQ(actual["lengths"][e], expected["lengths"][e]);
  }
  EXPECT_EQ(expected["lengths"][0].get<int>(), comparison.max_steps)
      << "the controller balances: full episodes";
}

TEST(SpineRollout, SameReturnsThroughTheSpineAsInProcess) {
  expect_same_returns_through_the_spine({.backend = "bullet",
                                         .env_id = "Upkie-Bullet-Pendulum",
                                         .spine_env_id = "Upkie-Spine-Pendulum"});
}

TEST(SpineRollout, SameReturnsThroughAMujocoSpine) {
  expect_same_returns_through_the_spine({.backend = "mujoco",
                                         .env_id = "Upkie-MuJoCo-Pendulum",
                                         .spine_env_id = "Upkie-Spine-Pendulum"});
}

// The world a spine hides from its agent (`--physics-option`) is the one the environments'
// options of the same names give: the velocity baseline through a spine with a payload and
// a slippery floor returns what it returns in process with those options. (The balancer is
// given, not "lqr": that one is designed on the environment, which in process knows the
// world. The spine's --action-delay delays servo commands, the environments' action_delay
// their actions, which the task also observes: tested in SpineServerTest instead.)
TEST(SpineRollout, TheSpinesHiddenWorldIsTheEnvironmentsOptions) {
  expect_same_returns_through_the_spine(
      {.backend = "bullet",
       .env_id = "Upkie-Bullet-Velocity",
       .spine_env_id = "Upkie-Spine-Velocity",
       .nb_substeps = 20,
       .controller = upkie_rl::testing::kVelocityBaseline,
       .max_steps = 150,
       .spine_world = {"--physics-option", "payload_mass=1", "--physics-option",
                       "payload_offset_x=0.04", "--physics-option", "floor_friction=0.6"},
       .env_options = " --env-option payload_mass=1 --env-option payload_offset_x=0.04"
                      " --env-option floor_friction=0.6"});
}

}  // namespace
