#include "sim/bullet_simulation.hpp"

#include <gtest/gtest.h>

#include "sim/servo_actions.hpp"

/// Bullet only; what every backend must do is in physics_behaviour_test.cpp.

namespace upkie_rl {
namespace {

std::shared_ptr<const RobotModel> model() { return RobotModel::default_model(); }

using testing::limp_action;

TEST(BulletSimulationTest, MergedAndUnmergedLinksAgree) {
  BulletConfig unmerged;
  unmerged.merge_fixed_links = false;
  BulletSimulation merged_simulation(model());
  BulletSimulation unmerged_simulation(model(), unmerged);
  for (int step = 0; step < 100; ++step) {
    merged_simulation.step(limp_action());
    unmerged_simulation.step(limp_action());
  }
  const Observation& merged = merged_simulation.observation();
  const Observation& reference = unmerged_simulation.observation();
  EXPECT_NEAR(merged.base_orientation.pitch, reference.base_orientation.pitch, 0.02);
  EXPECT_TRUE(merged.sim_base.position.isApprox(reference.sim_base.position, 1e-2));
}

}  // namespace
}  // namespace upkie_rl
