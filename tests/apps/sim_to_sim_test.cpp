/// Sim-to-sim: a pendulum policy trained on one physics engine balances on the other
/// (tests/data/policies/README.md says how the policies were trained).

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "apps/cli_runner.hpp"

namespace upkie_rl {
namespace {

using testing::run_cli;

/// Rollout summary of `policy` on `env_id` from the upright start, as the seed evaluates
/// (--exact-start: not the evaluations' random start).
/// (From tilted starts, init_rand_pitch=0.05, the MuJoCo-trained policy falls in about half
/// the episodes on either engine: a robustness matter, not a sim-to-sim one.)
nlohmann::json evaluate(const std::string& policy, const std::string& env_id) {
  const std::string path = std::string(UPKIE_RL_TEST_DATA_DIR) + "/policies/" + policy;
  const auto result = run_cli("rollout --env " + env_id + " --model " + path +
                              " --episodes 2 --exact-start --json");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  return nlohmann::json::parse(result.lines().back());
}

void expect_balances(const nlohmann::json& summary) {
  for (const auto& length : summary["lengths"]) EXPECT_EQ(length.get<int>(), 300) << summary;
  EXPECT_GT(summary["mean_return"].get<double>(), 290.0) << summary;
}

TEST(SimToSim, MujocoPolicyBalancesOnBullet) {
  expect_balances(evaluate("pendulum_mujoco_seed0.ckpt", "Upkie-MuJoCo-Pendulum"));
  expect_balances(evaluate("pendulum_mujoco_seed0.ckpt", "Upkie-Bullet-Pendulum"));
}

TEST(SimToSim, BulletPolicyBalancesOnMujoco) {
  expect_balances(evaluate("pendulum_bullet_seed0.ckpt", "Upkie-Bullet-Pendulum"));
  expect_balances(evaluate("pendulum_bullet_seed0.ckpt", "Upkie-MuJoCo-Pendulum"));
}

}  // namespace
}  // namespace upkie_rl
