/// Throughput of the Bullet and MuJoCo backends for one robot on one core, measured side by
/// side in one run: physics steps per second, and 200 Hz agent steps (5 physics steps each)
/// per second, while balancing.
#include <benchmark/benchmark.h>

#include <algorithm>

#include "sim/bullet_simulation.hpp"
#include "sim/mujoco_simulation.hpp"

namespace upkie_rl {
namespace {

/// Balancing law v = 10 theta + p + 0.1 p_dot, legs held straight.
ServoAction balance(const Observation& observation, double wheel_radius) {
  const double velocity =
      std::clamp(10.0 * observation.base_orientation.pitch + observation.wheel_odometry.position +
                     0.1 * observation.wheel_odometry.velocity,
                 -1.0, 1.0);
  ServoAction action{};
  for (std::size_t servo : {kLeftHip, kLeftKnee, kRightHip, kRightKnee}) {
    action[servo].position = 0.0;
  }
  action[kLeftWheel].velocity = velocity / wheel_radius;
  action[kRightWheel].velocity = -velocity / wheel_radius;
  return action;
}

void balance_loop(benchmark::State& state, PhysicsSimulation& simulation) {
  const double radius = simulation.model().wheel_radius();
  for (int warmup = 0; warmup < 200; ++warmup) {  // land on the wheels first
    simulation.step(balance(simulation.observation(), radius));
  }
  const long physics_start = simulation.physics_steps();
  for (auto _ : state) {
    benchmark::DoNotOptimize(simulation.step(balance(simulation.observation(), radius)));
  }
  state.counters["physics_steps_per_s"] = benchmark::Counter(
      static_cast<double>(simulation.physics_steps() - physics_start), benchmark::Counter::kIsRate);
}

void run_bullet(benchmark::State& state, int nb_substeps, bool merge_fixed_links) {
  BulletConfig config;
  config.nb_substeps = nb_substeps;
  config.merge_fixed_links = merge_fixed_links;
  BulletSimulation simulation(RobotModel::default_model(), config);
  balance_loop(state, simulation);
}

void run_mujoco(benchmark::State& state, int nb_substeps, int tire_condim) {
  MujocoConfig config;
  config.nb_substeps = nb_substeps;
  config.tire_condim = tire_condim;
  MujocoSimulation simulation(RobotModel::default_model(), config);
  balance_loop(state, simulation);
}

void BM_BulletPhysicsStep(benchmark::State& state) { run_bullet(state, 1, true); }
void BM_BulletAgentStep200Hz(benchmark::State& state) { run_bullet(state, 5, true); }
void BM_BulletPhysicsStepUnmerged(benchmark::State& state) { run_bullet(state, 1, false); }
void BM_MujocoPhysicsStep(benchmark::State& state) { run_mujoco(state, 1, 6); }
void BM_MujocoAgentStep200Hz(benchmark::State& state) { run_mujoco(state, 5, 6); }
void BM_MujocoAgentStep200HzCondim3(benchmark::State& state) { run_mujoco(state, 5, 3); }

BENCHMARK(BM_BulletPhysicsStep);
BENCHMARK(BM_BulletAgentStep200Hz);
BENCHMARK(BM_BulletPhysicsStepUnmerged);
BENCHMARK(BM_MujocoPhysicsStep);
BENCHMARK(BM_MujocoAgentStep200Hz);
BENCHMARK(BM_MujocoAgentStep200HzCondim3);

}  // namespace
}  // namespace upkie_rl
