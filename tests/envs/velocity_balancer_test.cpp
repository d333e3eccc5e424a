/// The velocity task's classical baseline: its law on hand-made observations, its design
/// on MuJoCo, and the residual mode of VelocityEnv that adds a policy to it.

#include "envs/controllers/velocity_balancer.hpp"
#include "common/velocity_baseline.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "envs/controllers/builtin_controllers.hpp"
#include "envs/controllers/velocity_balancer_design.hpp"
#include "envs/kinds/velocity_env.hpp"
#include "envs/registry/env_factory.hpp"
#include "envs/tasks/velocity_task.hpp"
#include "envs/tasks/velocity_tracking.hpp"

namespace upkie_rl {
namespace {

/// configs/velocity.yaml's base controller: `--controller lqr` designed on MuJoCo.
constexpr const char* kMujocoBaseline = testing::kVelocityBaseline;

/// A hand-made observation of the task without the height command (the balancer's legs
/// stay straight).
using Obs = std::array<float, VelocityTask::kObservationSize>;
/// An observation of the default task (with the height command).
using EnvObs = std::array<float, VelocityTask::kHeightObservationSize>;
using Act = std::array<float, VelocityTask::kActionSize>;

/// An upright observation (gravity straight down in the base frame) with a command.
Obs upright(float forward_velocity, float yaw_rate) {
  Obs observation{};
  observation[8] = -1.0f;  // gravity.z
  observation[VelocityTask::kCommandIndex] = forward_velocity;
  observation[VelocityTask::kCommandIndex + 1] = yaw_rate;
  return observation;
}

/// Resets `balancer` (a VelocityBalancer) and acts through its touchdown hold (wheels still,
/// whatever the observation says), so that the next act() is the law's first.
void reset_past_touchdown(Controller& balancer, double timestep) {
  balancer.reset();
  const auto hold = std::lround(VelocityBalancer::kTouchdownTime / timestep);
  Obs leaning = upright(1.0f, 1.0f);
  leaning[6] = 0.5f;  // gravity.x: leaning forward, which the law would answer
  for (long step = 0; step < hold; ++step) {
    Act action{};
    action.fill(0.5f);
    balancer.act(leaning, action);
    for (const float value : action) ASSERT_EQ(value, 0.0f) << "step " << step;
  }
}

TEST(VelocityBalancer, LawOfHandMadeObservations) {
  auto env = make_env("Upkie-Mock-Velocity", {{"height_command", "false"}});
  const double wheel_radius = find_velocity_env(*env)->servos().model().wheel_radius();
  const double scale = find_velocity_env(*env)->task().config().wheel_velocity_scale;
  VelocityBalancerGains gains;
  gains.feedback = {10.0, 1.0, 2.0, 0.5};
  gains.pitch_offset = 0.01;
  VelocityBalancer balancer(*env, gains);
  Act action{};
  // The wheels stay still while the robot lands, then the law acts.
  reset_past_touchdown(balancer, env->timestep());
  // Upright, still, no command: u = k_θ·(0 - θ₀), the same on both wheels (opposite
  // joint directions), legs at the default pose.
  balancer.act(upright(0.0f, 0.0f), action);
  EXPECT_NEAR(balancer.ground_velocity(), -10.0 * 0.01, 1e-9);
  EXPECT_NEAR(action[kLeftWheel], -0.1 / wheel_radius / scale, 1e-6);
  EXPECT_NEAR(action[kRightWheel], -action[kLeftWheel], 1e-6);
  EXPECT_EQ(action[kLeftHip], 0.0f);
  // Leaning forward by 0.1 rad: the wheels drive forward to catch the fall.
  reset_past_touchdown(balancer, env->timestep());
  Obs leaning = upright(0.0f, 0.0f);
  leaning[6] = static_cast<float>(std::sin(0.1));
  leaning[8] = static_cast<float>(-std::cos(0.1));
  balancer.act(leaning, action);
  EXPECT_NEAR(balancer.ground_velocity(), 10.0 * (0.1 - 0.01), 1e-6);
  // A forward command: the reference ramps (2 m/s² at 50 Hz: 0.04 m/s in the first step).
  reset_past_touchdown(balancer, env->timestep());
  balancer.act(upright(1.0f, 0.0f), action);
  const double reference = 0.04;
  const double error_integral = -reference * env->timestep();
  EXPECT_NEAR(balancer.ground_velocity(),
              reference + 10.0 * (0.0 - 0.01) + 2.0 * (0.0 - reference) + 0.5 * error_integral,
              1e-6);
  // A yaw-rate command turns both wheels the same way (joint convention).
  reset_past_touchdown(balancer, env->timestep());
  balancer.act(upright(0.0f, 1.0f), action);
  reset_past_touchdown(balancer, env->timestep());
  Act still{};
  balancer.act(upright(0.0f, 0.0f), still);
  EXPECT_LT(action[kLeftWheel] - still[kLeftWheel], -0.01f);
  EXPECT_NEAR(action[kLeftWheel] - still[kLeftWheel], action[kRightWheel] - still[kRightWheel],
              1e-6);
  EXPECT_THROW(VelocityBalancer(*make_env("Upkie-Mock-Pendulum"), gains), std::invalid_argument);
}

// The filters' gains are per 20 ms step: at another agent rate the balancer takes the gains
// of the same time constants, so that a velocity estimate has come as far after 0.2 s at
// 50, 100 or 200 Hz (at 100 Hz with the 20 ms gains it would come further: 0.80 of the
// way instead of 0.80^(1/2)).
TEST(VelocityBalancer, FiltersKeepTheirTimeConstantsAtAnyRate) {
  VelocityBalancerGains gains;
  gains.feedback = {10.0, 1.0, 2.0, 0.5};
  std::vector<double> estimates;
  for (const char* frequency : {"50", "100", "200"}) {
    auto env =
        make_env("Upkie-Mock-Velocity", {{"height_command", "false"}, {"frequency", frequency}});
    VelocityBalancer balancer(*env, gains);
    reset_past_touchdown(balancer, env->timestep());
    Obs rolling = upright(0.0f, 0.0f);
    rolling[4] = 10.0f;   // left wheel [rad/s]
    rolling[5] = -10.0f;  // right wheel: the opposite joint direction
    Act action{};
    const auto steps = std::lround(0.2 / env->timestep());
    for (long step = 0; step < steps; ++step) balancer.act(rolling, action);
    estimates.push_back(balancer.filtered_velocity());
  }
  EXPECT_GT(std::abs(estimates[0]), 0.1);
  EXPECT_NEAR(estimates[1], estimates[0], 1e-9);
  EXPECT_NEAR(estimates[2], estimates[0], 1e-9);
}

TEST(VelocityBalancerDesign, IdentifiedModelAndSteadyStateOnMujoco) {
  auto env = make_env("Upkie-MuJoCo-Velocity");
  VelocityBalancerGains bootstrap;
  bootstrap.feedback = {9.0, 0.3, 0.0, 0.4};
  // Standing under the hand-set law, as the design's first round.
  const VelocityBalanceModel standing = identify_velocity_balance(*env, bootstrap, 0.0, 0, 6);
  // Of 6 x 499: the hand-set law falls now and then on tires that grip (1342 kept,
  // measured; over 2000 when MuJoCo's tires slipped).
  EXPECT_GT(standing.samples, 1000);
  // θ integrates θ̇: 0.013 for a 0.02 s step (measured) since the tires' rolling resistance
  // damps the pitch rate within the step (0.16 of it is left after one, A(1, 1)).
  EXPECT_GT(standing.A(0, 1), 0.5 * env->timestep());
  EXPECT_LT(standing.A(0, 1), 1.3 * env->timestep());
  EXPECT_LT(standing.B(1), 0.0);  // the wheels speeding up tip the body backward
  EXPECT_GT(standing.B(2), 0.0);  // and the (filtered) wheel velocity follows the command
  const VelocityBalancerGains first = velocity_balancer_for(standing, env->timestep(), {});
  EXPECT_GT(first.feedback[0], 0.0);  // leaning forward drives forward
  // Driving at up to 0.8 m/s under the first design, as the second round.
  const VelocityBalanceModel model = identify_velocity_balance(*env, first, 0.8, 1000, 10);
  // Of 10 x 499: the first design falls now and then (1250 kept, measured, on the tires
  // with rolling resistance; 1996 of 4 x 499 on free-rolling ones, 533 when they slipped).
  EXPECT_GT(model.samples, 600);
  const VelocityBalancerGains gains = velocity_balancer_for(model, env->timestep(), {});
  // Driving at v needs about v of ground velocity command (0.999, measured) and a slight
  // forward lean (0.015 rad per m/s: the velocity task's MuJoCo tires have no rolling
  // friction; 0.1 when they slipped).
  EXPECT_NEAR(gains.command_per_velocity, 1.0, 0.3);
  EXPECT_GT(gains.pitch_per_velocity, 0.0);
  EXPECT_LT(gains.pitch_per_velocity, 0.3);
  // The design leaves the environment on random commands again.
  EXPECT_FALSE(find_velocity_env(*env)->command_override().has_value());
  EXPECT_THROW(identify_velocity_balance(*make_env("Upkie-Mock-Pendulum"), bootstrap, 0.5, 0, 1),
               std::invalid_argument);
  VelocityBalancerWeights bad;
  bad.max_pitch = 0.0;
  EXPECT_THROW(velocity_balancer_for(model, env->timestep(), bad), std::invalid_argument);
}

/// A controller of `spec` driving environment `id` from reset (seed 0) under a command
/// override, one agent step per step().
struct DrivenRun {
  std::unique_ptr<Env> env;
  VelocityEnv* velocity;
  std::unique_ptr<Controller> controller;
  EnvObs observation{};
  Act action{};

  DrivenRun(const std::string& id, const std::string& spec, const VelocityCommand& command)
      : env(make_env(id)),
        velocity(find_velocity_env(*env)),
        controller(make_builtin_controller(spec, *env)) {
    velocity->set_command_override(command);
    env->reset(0, observation);
    controller->reset();
  }
  /// Acts and steps; the step's result.
  StepResult step() {
    controller->act(observation, action);
    return env->step(action, observation);
  }
};

/// RMS forward error, against the followed (ramped) command, of `spec` driving MuJoCo to
/// 0.8 m/s, then back to -0.4 m/s, at the default 1 m/s² (5 s, nominal conditions).
double ramp_tracking_error(const std::string& spec) {
  DrivenRun run("Upkie-MuJoCo-Velocity", spec, VelocityCommand{0.8, 0.0});
  VelocityTracking tracking;
  for (int step = 0; step < 250; ++step) {
    if (step == 125) run.velocity->set_command_override(VelocityCommand{-0.4, 0.0});
    const StepResult result = run.step();
    tracking.add(*run.velocity, result.terminated);
    if (result.terminated) return 1e9;
  }
  return tracking.rms_forward();
}

TEST(VelocityBalancer, TracksARampedCommandWithItsAccelerationFeedforward) {
  // configs/velocity.yaml's base controller, designed by `--controller lqr` on MuJoCo, with
  // and without its last two numbers (the acceleration feedforward).
  const std::string law =
      "balancer:10.3236647,0.264768692,2.80279398,0.601664129,0.0183275488,0.0133529685,"
      "-0.000164539185,1.00066929";
  const double with_feedforward = ramp_tracking_error(kMujocoBaseline);
  ASSERT_EQ(std::string(kMujocoBaseline).rfind(law, 0), 0u);
  const double without = ramp_tracking_error(law);
  // Measured: 0.151 m/s with it on the tires with rolling resistance (0.116 on
  // free-rolling ones, 0.185 when they slipped), at least 15 % below the law without it (the
  // ramp's start and end, where the robot must lean first, make most of either).
  EXPECT_LT(with_feedforward, 0.18);
  EXPECT_LT(with_feedforward, 0.85 * without) << with_feedforward << " against " << without;
}

/// Mean measured forward velocity and yaw rate of `controller` on MuJoCo over [from, to)
/// seconds of: 1 m/s straight for 4 s, then 0.5 m/s while turning at 1 rad/s (commands
/// ramped at the task's 1 m/s²; fall: NaN).
BaseVelocity mean_velocity_turning_after_a_fast_run(const std::string& spec, double from,
                                                    double to) {
  DrivenRun run("Upkie-MuJoCo-Velocity", spec, VelocityCommand{1.0, 0.0});
  BaseVelocity sum;
  int samples = 0;
  const auto steps = std::lround(to / run.env->timestep());
  for (long step = 0; step < steps; ++step) {
    const double time = static_cast<double>(step + 1) * run.env->timestep();
    if (time > 4.0) run.velocity->set_command_override(VelocityCommand{0.5, 1.0});
    if (run.step().terminated) return {std::nan(""), std::nan("")};
    if (time <= from) continue;
    sum.forward_velocity += run.velocity->measured_velocity().forward_velocity;
    sum.yaw_rate += run.velocity->measured_velocity().yaw_rate;
    ++samples;
  }
  return {sum.forward_velocity / samples, sum.yaw_rate / samples};
}

// The classical baseline (designed on MuJoCo by `lqr`) keeps its forward velocity while it
// turns after a fast run. Before MuJoCo's velocity task had tires that roll without
// slipping, the odometry read the 1 m/s run 1.45 times too fast, the balancer's velocity
// integral stored the difference as distance ahead (1.4 m by the end of the run) and paid
// it back over the next seconds: 0.15 m/s instead of 0.5 (the same without the turn).
TEST(VelocityBalancer, KeepsItsForwardVelocityWhileTurningAfterAFastRun) {
  const std::string designed =
      resolve_controller_spec("lqr", [] { return make_env("Upkie-MuJoCo-Velocity"); });
  const BaseVelocity mean = mean_velocity_turning_after_a_fast_run(designed, 5.0, 7.0);
  // Measured: 0.469 m/s and 0.996 rad/s (before: 0.153 m/s and 0.976 rad/s).
  EXPECT_NEAR(mean.forward_velocity, 0.5, 0.1);
  EXPECT_NEAR(mean.yaw_rate, 1.0, 0.1);
}

// MuJoCo's velocity task has tires that roll: driving straight, the base travels the
// distance the wheels roll, as on Bullet. With MuJoCo's rolling friction in the tire
// contact (dimension 6, the other tasks') they slipped by a third: an effective radius of
// 0.035 m for 0.050 m.
TEST(VelocityEnv, MujocoTiresRollWithoutSlipping) {
  for (const char* id : {"Upkie-MuJoCo-Velocity", "Upkie-Bullet-Velocity"}) {
    DrivenRun run(id, kMujocoBaseline, VelocityCommand{0.5, 0.0});
    const Env& env = *run.env;
    Eigen::Vector3d start;
    double start_angle = 0.0;
    const auto wheel_angle = [&env]() {  // forward roll [rad], left and right averaged
      const Observation& full = *env.full_observation();
      return 0.5 * (full.servo[kLeftWheel].position - full.servo[kRightWheel].position);
    };
    for (int step = 0; step < 250; ++step) {  // 5 s: 2 s to settle at 0.5 m/s, then 3 s
      if (step == 100) {
        start = env.full_observation()->sim_base.position;
        start_angle = wheel_angle();
      }
      ASSERT_FALSE(run.step().terminated) << id;
    }
    const double distance = (env.full_observation()->sim_base.position - start).head<2>().norm();
    const double radius = run.velocity->servos().model().wheel_radius();
    // Measured: 0.0499 m on MuJoCo (0.0349 with rolling friction), 0.0511 m on Bullet.
    EXPECT_NEAR(distance / (wheel_angle() - start_angle), radius, 0.05 * radius) << id;
    EXPECT_GT(distance, 1.2) << id;  // it drove 1.64 m on MuJoCo, 1.42 m on Bullet
  }
}

TEST(VelocityBalancer, SpecsOfEightOrTenNumbers) {
  auto env = make_env("Upkie-Mock-Velocity", {{"height_command", "false"}});
  EXPECT_NO_THROW(make_builtin_controller("balancer:10,1,2,0.5,0.01,0.1,0,1", *env));
  EXPECT_NO_THROW(make_builtin_controller("balancer:10,1,2,0.5,0.01,0.1,0,1,0.03,0.1", *env));
  for (const char* spec :
       {"balancer:10,1,2,0.5,0.01,0.1,0,1,0.03", "balancer:10,1,2,0.5,0.01,0.1,0,1,0.03,0.1,7",
        "balancer:10,1,2,0.5,0.01,0.1,0,1,nan,0.1"}) {
    try {
      make_builtin_controller(spec, *env);
      ADD_FAILURE() << spec << " was accepted";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("eight or ten finite numbers"), std::string::npos)
          << error.what();
    }
  }
  // The acceleration feedforward of a ten-number spec acts: the same upright observation,
  // the reference accelerating, leans the reference (θ_a) and leads the wheels (u_a).
  Act with_feedforward{};
  Act without{};
  Obs ramping = upright(1.0f, 0.0f);
  auto leaning = make_builtin_controller("balancer:10,0,0,0,0,0,0,1,0.1,0.2", *env);
  auto plain = make_builtin_controller("balancer:10,0,0,0,0,0,0,1", *env);
  reset_past_touchdown(*leaning, env->timestep());
  reset_past_touchdown(*plain, env->timestep());
  leaning->act(ramping, with_feedforward);
  plain->act(ramping, without);
  // a_ref after one step: 0.3 · (0.04 m/s / 0.02 s) = 0.6 m/s²: u differs by
  // (0.2 - 10·0.1)·0.6 = -0.48 m/s.
  const double wheel_radius = find_velocity_env(*env)->servos().model().wheel_radius();
  const double scale = find_velocity_env(*env)->task().config().wheel_velocity_scale;
  EXPECT_NEAR(with_feedforward[kLeftWheel] - without[kLeftWheel], -0.48 / wheel_radius / scale,
              1e-5);
}

TEST(VelocityEnv, ResidualModeAddsTheScaledActionToTheBase) {
  const std::string base = "balancer:10,1,2,0.5,0.01,0,0,1";
  auto residual =
      make_env("Upkie-Mock-Velocity", {{"base_controller", base}, {"residual_scale", "0.5"}});
  auto plain = make_env("Upkie-Mock-Velocity");
  EnvObs observation{};
  EnvObs plain_observation{};
  residual->reset(3, observation);
  plain->reset(3, plain_observation);
  VelocityBalancer balancer(*plain, {{10, 1, 2, 0.5}, 0.01, 0.0, 0.0, 1.0});
  Act base_action{};
  balancer.act(plain_observation, base_action);
  Act agent{};
  agent[kLeftWheel] = 0.2f;
  agent[kLeftHip] = -0.4f;
  residual->step(agent, observation);
  // The observation's last action is what was sent: base + 0.5 · agent.
  const std::size_t last_action = 12;
  EXPECT_NEAR(observation[last_action + kLeftWheel], base_action[kLeftWheel] + 0.1f, 1e-5);
  EXPECT_NEAR(observation[last_action + kRightWheel], base_action[kRightWheel], 1e-5);
  EXPECT_NEAR(observation[last_action + kLeftHip], -0.2f, 1e-6);
}

}  // namespace
}  // namespace upkie_rl
