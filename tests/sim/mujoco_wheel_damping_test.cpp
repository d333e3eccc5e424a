/// MujocoConfig::implicit_wheel_damping: the wheels' velocity loop, unstable when its
/// damping is explicit against the wheel's own spin inertia, settles when MuJoCo integrates
/// that damping implicitly; the servo law's torque and its limits stay the same.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "servo_actions.hpp"
#include "sim/mujoco_simulation.hpp"

namespace upkie_rl {
namespace {

using testing::pendulum_action;

/// A robot in the air (no floor) whose left wheel is asked for 5 rad/s at kd_scale 1.
struct WheelInTheAir {
  explicit WheelInTheAir(bool implicit) {
    MujocoConfig config;
    config.floor = false;
    config.implicit_wheel_damping = implicit;
    simulation = std::make_unique<MujocoSimulation>(RobotModel::default_model(), config);
    action = pendulum_action(0.0, 0.05);
    action[kLeftWheel].velocity = 5.0;
  }

  /// The largest |v - 5| [rad/s] over the last 20 of `steps` agent steps.
  double late_error(int steps) {
    double error = 0.0;
    for (int step = 0; step < steps; ++step) {
      simulation->step(action);
      if (step >= steps - 20) {
        error =
            std::max(error, std::abs(simulation->observation().servo[kLeftWheel].velocity - 5.0));
      }
    }
    return error;
  }

  std::unique_ptr<MujocoSimulation> simulation;
  ServoAction action;
};

TEST(MujocoWheelDamping, ExplicitDampingChattersAndImplicitSettles) {
  // kd·dt/I = 1 N.m.s/rad × 1 ms / 2.6e-4 kg.m² ≈ 3.8, above the explicit bound of 2.
  WheelInTheAir explicit_damping(false);
  WheelInTheAir implicit_damping(true);
  EXPECT_GT(explicit_damping.late_error(60), 1.0);
  EXPECT_LT(implicit_damping.late_error(60), 0.01);
}

TEST(MujocoWheelDamping, TheServoTorqueAndItsLimitAreKept) {
  WheelInTheAir wheel(true);
  // Far from its target the servo saturates: the limit holds, whatever the damping.
  wheel.action[kLeftWheel].velocity = 100.0;
  wheel.simulation->step(wheel.action);
  EXPECT_NEAR(wheel.simulation->observation().servo[kLeftWheel].torque, 1.7, 1e-9);
  // Settled, the reported torque is the law's kd·(v* - v) (tiny: no load in the air).
  wheel.action[kLeftWheel].velocity = 5.0;
  wheel.late_error(60);
  const ServoObservation& servo = wheel.simulation->observation().servo[kLeftWheel];
  EXPECT_NEAR(servo.torque, 1.0 * (5.0 - servo.velocity), 1e-3);
}

TEST(MujocoWheelDamping, AVariedEpisodeLeavesNothingToTheNext) {
  // The simulation's own model copy carries both the damping and an episode's masses; an
  // episode without variation after a heavy one replays a fresh simulation's exactly.
  MujocoConfig config;
  config.implicit_wheel_damping = true;
  const ServoAction action = pendulum_action(0.2, 0.05);
  const auto run = [&action](MujocoSimulation& simulation) {
    simulation.reset(ResetState{});
    for (int step = 0; step < 40; ++step) simulation.step(action);
    return simulation.observation().sim_base.position;
  };
  MujocoSimulation fresh(RobotModel::default_model(), config);
  const Eigen::Vector3d nominal = run(fresh);
  MujocoSimulation reused(RobotModel::default_model(), config);
  PhysicsVariation heavy;
  heavy.mass_scale.fill(1.5);
  reused.set_variation(heavy);
  const Eigen::Vector3d heavy_position = run(reused);
  reused.set_variation(PhysicsVariation{});
  EXPECT_EQ(run(reused), nominal);
  EXPECT_NE(heavy_position, nominal);
}

}  // namespace
}  // namespace upkie_rl
