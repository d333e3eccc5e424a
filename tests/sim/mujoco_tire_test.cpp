/// MuJoCo's tires (MujocoConfig): sliding friction only in the friction cone (contact
/// dimension 3) so that a driven tire rolls without slipping, and the URDF's rolling
/// resistance as a torque of its own, as Bullet has it. Measured against the same robot
/// with free-rolling tires, and against Bullet.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sim/bullet_simulation.hpp"
#include "sim/mujoco_simulation.hpp"
#include "sim/servo_actions.hpp"

namespace upkie_rl {
namespace {

using testing::limp_action;
using testing::pendulum_action;

MujocoConfig tires(bool rolling_resistance) {
  MujocoConfig config;
  config.tire_rolling_resistance = rolling_resistance;
  return config;
}

/// Largest |pitch| [rad] under v = 10 θ + p + 0.1 ṗ for 10 s, or past 1 rad: a fall.
double pendulum_law_max_pitch(PhysicsSimulation& simulation) {
  const double radius = simulation.model().wheel_radius();
  double max_pitch = 0.0;
  simulation.reset(ResetState{});
  const int steps = static_cast<int>(10.0 / simulation.agent_timestep());
  for (int step = 0; step < steps && max_pitch < 1.0; ++step) {
    const Observation& observation = simulation.observation();
    const double velocity = 10.0 * observation.base_orientation.pitch +
                            observation.wheel_odometry.position +
                            0.1 * observation.wheel_odometry.velocity;
    simulation.step(pendulum_action(std::clamp(velocity, -1.0, 1.0), radius));
    max_pitch = std::max(max_pitch, std::abs(simulation.observation().base_orientation.pitch));
  }
  return max_pitch;
}

/// Seconds until a limp robot released upright pitches past 1 rad (5 at most).
double limp_fall_time(PhysicsSimulation& simulation) {
  simulation.reset(ResetState{});
  while (simulation.observation().time < 5.0 &&
         std::abs(simulation.observation().base_orientation.pitch) < 1.0) {
    simulation.step(limp_action());
  }
  return simulation.observation().time;
}

TEST(MujocoTires, RollingResistanceMakesThemBehaveAsBulletsTires) {
  const auto robot = RobotModel::default_model();
  MujocoSimulation resisting(robot, tires(true));
  MujocoSimulation free_rolling(robot, tires(false));
  BulletSimulation bullet(robot, BulletConfig{});
  // Measured: 0.014 rad with the resistance, 0.015 on Bullet; free-rolling tires drift
  // and fall after about 6 s.
  const double bullet_pitch = pendulum_law_max_pitch(bullet);
  EXPECT_LT(pendulum_law_max_pitch(resisting), 2.0 * bullet_pitch);
  EXPECT_GT(pendulum_law_max_pitch(free_rolling), 1.0);
  // Measured: 0.81 s with the resistance, 0.91 s on Bullet; on free-rolling tires the
  // robot, released exactly upright, rolls upright past 5 s.
  EXPECT_NEAR(limp_fall_time(resisting), limp_fall_time(bullet), 0.3);
  EXPECT_GE(limp_fall_time(free_rolling), 5.0);
}

TEST(MujocoTires, TheRobotsTiresAreTheDefaults) {
  const MujocoConfig config;
  EXPECT_EQ(config.tire_condim, 3);
  EXPECT_TRUE(config.tire_rolling_resistance);
  EXPECT_TRUE(config.implicit_wheel_damping);
}

}  // namespace
}  // namespace upkie_rl
