/// Checks that environment steps allocate nothing (hot-path rule), on the Mock backend and
/// on MuJoCo, whose engine steps in the arena of its mjData (the Bullet engine's own
/// allocations are the sim layer's business).

#include <gtest/gtest.h>

#include "common/allocation_counter.hpp"
#include "common/velocity_baseline.hpp"

#include <vector>

#include "envs/registry/env_factory.hpp"

namespace upkie_rl {
namespace {

/// Allocations during 100 steps of the neutral action, after a reset and a warm-up step.
std::size_t allocations_in_100_steps(Env& env) {
  std::vector<float> observation(env.observation_space().size());
  std::vector<float> action(env.action_space().size());
  env.neutral_action(action);
  env.reset(0, observation);
  env.step(action, observation);  // warm-up
  const std::size_t before = testing::all_threads_allocations.load();
  for (int step = 0; step < 100; ++step) env.step(action, observation);
  return testing::all_threads_allocations.load() - before;
}

TEST(AllocationFree, EnvironmentStepsAllocateNothing) {
  for (const char* id : {"Upkie-Mock-Servos", "Upkie-Mock-Pendulum", "Upkie-Mock-Gyropod",
                         "Upkie-Mock-ServosTask", "Upkie-MuJoCo-Servos", "Upkie-MuJoCo-Pendulum",
                         "Upkie-MuJoCo-Gyropod", "Upkie-MuJoCo-ServosTask"}) {
    auto env = make_env(id);
    EXPECT_EQ(allocations_in_100_steps(*env), 0u) << id;
  }
}

TEST(AllocationFree, PerturbedStepsAllocateNothingEither) {
  // Every perturbation on, pushes during the steps measured, resets excluded (a varied
  // MuJoCo model is copied once, at the first reset).
  const EnvOptions perturbed = {{"inertia_variation", "0.2"},
                                {"joint_friction", "0.01"},
                                {"torque_control_noise", "0.05"},
                                {"torque_measurement_noise", "0.05"},
                                {"imu_gyroscope_noise", "0.01"},
                                {"imu_accelerometer_bias", "0.1"},
                                {"floor_friction_variation", "0.2"},
                                {"slope_pitch", "5"},
                                {"slope_roll", "-3"},
                                {"payload_mass", "1"},
                                {"payload_offset_x", "0.05"},
                                {"push_force", "10"},
                                {"push_start", "0"},
                                {"push_interval", "0.2"},
                                {"observation_noise", "0.01"},
                                {"action_lag_max", "0.03"},
                                {"action_delay", "2"},
                                {"observation_history", "4"}};
  for (const char* id :
       {"Upkie-MuJoCo-Servos", "Upkie-MuJoCo-Pendulum", "Upkie-MuJoCo-ServosTask"}) {
    auto env = make_env(id, perturbed);
    EXPECT_EQ(allocations_in_100_steps(*env), 0u) << id;
  }
}

TEST(AllocationFree, AResidualVelocityPolicysStepsAllocateNothing) {
  // configs/velocity.yaml's way of acting: the classical balancer plus the agent's
  // filtered correction, faded with the tilt, over the last three observations.
  const EnvOptions residual = {{"base_controller", testing::kVelocityBaseline},
                               {"residual_scale", "0.3"},
                               {"residual_filter", "0.02"},
                               {"residual_fade_start", "0.25"},
                               {"residual_fade_end", "0.35"},
                               {"observe_acceleration", "true"},
                               {"observation_history", "3"}};
  for (const char* id : {"Upkie-Mock-Velocity", "Upkie-MuJoCo-Velocity"}) {
    auto env = make_env(id, residual);
    EXPECT_EQ(allocations_in_100_steps(*env), 0u) << id;
  }
}

TEST(AllocationFree, CounterCounts) {
  const std::size_t before = testing::all_threads_allocations.load();
  auto* leak_check = new std::vector<int>(10);
  delete leak_check;
  EXPECT_GE(testing::all_threads_allocations.load() - before, 2u);
}

}  // namespace
}  // namespace upkie_rl
