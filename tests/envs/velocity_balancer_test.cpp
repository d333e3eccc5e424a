/// The velocity task's classical baseline: its law on hand-made observations, its design
/// on MuJoCo, and the residual mode of VelocityEnv that adds a policy to it.

#include "envs/velocity_balancer.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "envs/builtin_controllers.hpp"
#include "envs/registry.hpp"
#include "envs/velocity_balancer_design.hpp"
#include "envs/velocity_env.hpp"
#include "envs/velocity_task.hpp"
#include "envs/velocity_tracking.hpp"

namespace upkie_rl {
namespace {

using Obs = std::array<float, VelocityTask::kObservationSize>;
using Act = std::array<float, VelocityTask::kActionSize>;

/// An upright observation (gravity straight down in the base frame) with a command.
Obs upright(float forward_velocity, float yaw_rate) {
  Obs observation{};
  observation[8] = -1.0f;  // gravity.z
  observation[VelocityTask::kCommandIndex] = forward_velocity;
  observation[VelocityTask::kCommandIndex + 1] = yaw_rate;
  return observation;
}

TEST(VelocityBalancer, LawOfHandMadeObservations) {
  auto env = make_env("Upkie-Mock-Velocity");
  const double wheel_radius = find_velocity_env(*env)->servos().model().wheel_radius();
  const double scale = find_velocity_env(*env)->task().config().wheel_velocity_scale;
  VelocityBalancerGains gains;
  gains.feedback = {10.0, 1.0, 2.0, 0.5};
  gains.pitch_offset = 0.01;
  VelocityBalancer balancer(*env, gains);
  Act action{};
  // Upright, still, no command: u = k_θ·(0 - θ₀), the same on both wheels (opposite
  // joint directions), legs at the default pose.
  balancer.act(upright(0.0f, 0.0f), action);
  EXPECT_NEAR(balancer.ground_velocity(), -10.0 * 0.01, 1e-9);
  EXPECT_NEAR(action[kLeftWheel], -0.1 / wheel_radius / scale, 1e-6);
  EXPECT_NEAR(action[kRightWheel], -action[kLeftWheel], 1e-6);
  EXPECT_EQ(action[kLeftHip], 0.0f);
  // Leaning forward by 0.1 rad: the wheels drive forward to catch the fall.
  balancer.reset();
  Obs leaning = upright(0.0f, 0.0f);
  leaning[6] = static_cast<float>(std::sin(0.1));
  leaning[8] = static_cast<float>(-std::cos(0.1));
  balancer.act(leaning, action);
  EXPECT_NEAR(balancer.ground_velocity(), 10.0 * (0.1 - 0.01), 1e-6);
  // A forward command: the reference ramps (2 m/s² at 50 Hz: 0.04 m/s in the first step).
  balancer.reset();
  balancer.act(upright(1.0f, 0.0f), action);
  const double reference = 0.04;
  const double error_integral = -reference * env->timestep();
  EXPECT_NEAR(balancer.ground_velocity(),
              reference + 10.0 * (0.0 - 0.01) + 2.0 * (0.0 - reference) + 0.5 * error_integral,
              1e-6);
  // A yaw-rate command turns both wheels the same way (joint convention).
  balancer.reset();
  balancer.act(upright(0.0f, 1.0f), action);
  balancer.reset();
  Act still{};
  balancer.act(upright(0.0f, 0.0f), still);
  EXPECT_LT(action[kLeftWheel] - still[kLeftWheel], -0.01f);
  EXPECT_NEAR(action[kLeftWheel] - still[kLeftWheel], action[kRightWheel] - still[kRightWheel],
              1e-6);
  EXPECT_THROW(VelocityBalancer(*make_env("Upkie-Mock-Pendulum"), gains), std::invalid_argument);
}

TEST(VelocityBalancerDesign, IdentifiedModelAndSteadyStateOnMujoco) {
  auto env = make_env("Upkie-MuJoCo-Velocity");
  VelocityBalancerGains bootstrap;
  bootstrap.feedback = {9.0, 0.3, 0.0, 0.4};
  // Standing under the hand-set law, as the design's first round.
  const VelocityBalanceModel standing = identify_velocity_balance(*env, bootstrap, 0.0, 0, 6);
  EXPECT_GT(standing.samples, 2000);  // of 6 x 499: it mostly stays up
  EXPECT_NEAR(standing.A(0, 1), env->timestep(), 0.3 * env->timestep());  // θ integrates θ̇
  EXPECT_LT(standing.B(1), 0.0);  // the wheels speeding up tip the body backward
  EXPECT_GT(standing.B(2), 0.0);  // and the (filtered) wheel velocity follows the command
  const VelocityBalancerGains first = velocity_balancer_for(standing, env->timestep(), {});
  EXPECT_GT(first.feedback[0], 0.0);  // leaning forward drives forward
  // Driving at up to 0.8 m/s under the first design, as the second round.
  const VelocityBalanceModel model = identify_velocity_balance(*env, first, 0.8, 1000, 4);
  // Of 4 x 499: the first design falls now and then (533 kept, measured).
  EXPECT_GT(model.samples, 400);
  const VelocityBalancerGains gains = velocity_balancer_for(model, env->timestep(), {});
  // Driving at v needs about v of ground velocity command and a forward lean against the
  // rolling losses.
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

/// RMS forward error, against the followed (ramped) command, of `spec` driving MuJoCo to
/// 0.8 m/s, then back to -0.4 m/s, at the default 1 m/s² (5 s, nominal conditions).
double ramp_tracking_error(const std::string& spec) {
  auto env = make_env("Upkie-MuJoCo-Velocity");
  VelocityEnv* velocity = find_velocity_env(*env);
  std::unique_ptr<Controller> controller = make_builtin_controller(spec, *env);
  Obs observation{};
  Act action{};
  velocity->set_command_override(VelocityCommand{0.8, 0.0});
  env->reset(0, observation);
  controller->reset();
  VelocityTracking tracking;
  for (int step = 0; step < 250; ++step) {
    if (step == 125) velocity->set_command_override(VelocityCommand{-0.4, 0.0});
    controller->act(observation, action);
    const StepResult result = env->step(action, observation);
    tracking.add(*velocity, result.terminated);
    if (result.terminated) return 1e9;
  }
  return tracking.rms_forward();
}

TEST(VelocityBalancer, TracksARampedCommandWithItsAccelerationFeedforward) {
  // configs/velocity.yaml's base controller, designed by `--controller lqr` on MuJoCo, with
  // and without its last two numbers (the acceleration feedforward).
  const std::string law =
      "balancer:23.2262089,0.928787843,2.34776379,1.16682061,0.0183203909,0.100014353,"
      "0.000137691062,1.03630242";
  const double with_feedforward = ramp_tracking_error(law + ",0.0273933494,0.136876654");
  const double without = ramp_tracking_error(law);
  // Measured: 0.185 m/s with it, 0.257 m/s without (the ramp's start and end, where the
  // robot must lean first, make most of either).
  EXPECT_LT(with_feedforward, 0.22);
  EXPECT_LT(with_feedforward, 0.85 * without);
}

TEST(VelocityBalancer, SpecsOfEightOrTenNumbers) {
  auto env = make_env("Upkie-Mock-Velocity");
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
  Obs observation{};
  Obs plain_observation{};
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
