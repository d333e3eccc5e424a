/// Perturbation options of the environments: off they are the unperturbed environment bit
/// for bit, seeded they repeat, and each changes what it should (pushes push, noise stays
/// within its bounds and off the reward, delay delays, lag filters).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "common/error_message.hpp"
#include "common/velocity_baseline.hpp"
#include "envs/controllers/builtin_controllers.hpp"
#include "envs/kinds/servos_env.hpp"
#include "envs/randomization/action_lag.hpp"
#include "envs/randomization/perturbation_settings.hpp"
#include "envs/randomization/residual_lag.hpp"
#include "envs/registry/env_factory.hpp"
#include "envs/registry/registry.hpp"
#include "envs/tasks/velocity_task.hpp"
#include "envs/wrappers/env_wrapper.hpp"
#include "sim/servo_command_fields.hpp"

namespace upkie_rl {
namespace {

/// What an episode of the PD law gives: observations, rewards and base positions.
struct Trace {
  std::vector<std::vector<float>> observations;
  std::vector<double> rewards;
  std::vector<Eigen::Vector3d> base_positions;
  bool operator==(const Trace& other) const {
    return observations == other.observations && rewards == other.rewards &&
           base_positions == other.base_positions;
  }
};

/// Runs `steps` steps of `env` from reset(seed), the action given by `act`.
Trace run(Env& env, std::uint64_t seed, int steps,
          const std::function<float(const std::vector<float>&, int)>& act) {
  Trace trace;
  std::vector<float> observation(env.observation_space().size());
  std::vector<float> action(env.action_space().size(), 0.0f);
  env.reset(seed, observation);
  trace.observations.push_back(observation);
  for (int step = 0; step < steps; ++step) {
    action[0] = act(observation, step);
    const StepResult result = env.step(action, observation);
    trace.observations.push_back(observation);
    trace.rewards.push_back(result.reward);
    trace.base_positions.push_back(env.full_observation()->sim_base.position);
    if (result.terminated || result.truncated) break;
  }
  return trace;
}

float pd(const std::vector<float>& o, int) { return 10.0f * o[0] + o[1] + 0.1f * o[3]; }

Trace pd_trace(const std::string& id, const EnvOptions& options, std::uint64_t seed = 3,
               int steps = 300) {
  auto env = make_env(id, options);
  return run(*env, seed, steps, pd);
}

const EnvOptions kEverythingOff = {{"mass_scale", "1"},
                                   {"inertia_variation", "0"},
                                   {"joint_friction", "0"},
                                   {"joint_friction_fixed", "0"},
                                   {"wheel_servo_gain_scale", "1"},
                                   {"leg_servo_gain_scale", "1"},
                                   {"imu_gyroscope_bias_fixed_x", "0"},
                                   {"imu_gyroscope_bias_fixed_y", "0"},
                                   {"imu_gyroscope_bias_fixed_z", "0"},
                                   {"torque_control_noise", "0"},
                                   {"torque_measurement_noise", "0"},
                                   {"imu_accelerometer_bias", "0"},
                                   {"imu_gyroscope_noise", "0"},
                                   {"floor_friction", "1"},
                                   {"floor_friction_variation", "0"},
                                   {"slope_pitch", "0"},
                                   {"slope_roll", "0"},
                                   {"payload_mass", "0"},
                                   {"payload_offset_x", "0"},
                                   {"payload_offset_y", "0"},
                                   {"payload_offset_z", "0"},
                                   {"push_force", "0"},
                                   {"observation_noise", "0"},
                                   {"action_lag_max", "0"},
                                   {"action_delay", "0"}};

const EnvOptions kEverythingOn = {{"inertia_variation", "0.2"},
                                  {"joint_friction", "0.01"},
                                  {"torque_control_noise", "0.05"},
                                  {"torque_measurement_noise", "0.05"},
                                  {"imu_accelerometer_bias", "0.1"},
                                  {"imu_gyroscope_bias", "0.01"},
                                  {"imu_gyroscope_noise", "0.01"},
                                  {"floor_friction_variation", "0.3"},
                                  {"push_force", "20"},
                                  {"observation_noise", "0.01"},
                                  {"action_lag_max", "0.03"},
                                  {"action_delay", "1"},
                                  {"init_rand_pitch", "0.1"}};

class EnginePerturbations : public ::testing::TestWithParam<const char*> {
 protected:
  std::string id(const char* kind = "Pendulum") const {
    return std::string("Upkie-") + GetParam() + "-" + kind;
  }
};

TEST_P(EnginePerturbations, OffIsTheUnperturbedEnvironmentBitForBit) {
  EXPECT_TRUE(pd_trace(id(), {}) == pd_trace(id(), kEverythingOff));
}

TEST_P(EnginePerturbations, ScaleZeroIsTheUnperturbedEnvironmentBitForBit) {
  auto env = make_env(id(), kEverythingOn);
  env->set_randomization_scale(0.0);
  EXPECT_TRUE(run(*env, 3, 300, pd) == pd_trace(id(), {}));
  env->set_randomization_scale(1.0);
  EXPECT_FALSE(run(*env, 3, 300, pd) == pd_trace(id(), {}));
}

TEST_P(EnginePerturbations, SameSeedSamePerturbationsOtherSeedOthers) {
  const Trace first = pd_trace(id(), kEverythingOn, 5);
  EXPECT_TRUE(first == pd_trace(id(), kEverythingOn, 5));
  EXPECT_FALSE(first == pd_trace(id(), kEverythingOn, 6));
  // A reset without a seed continues the generators: the next episode differs.
  auto env = make_env(id(), kEverythingOn);
  const Trace seeded = run(*env, 5, 300, pd);
  std::vector<float> observation(4);
  env->reset(std::nullopt, observation);
  EXPECT_NE(observation, seeded.observations.front());
}

TEST_P(EnginePerturbations, PushesMoveTheRobotInTheirDirection) {
  // One push of 30 N for 0.1 s starting between 0.25 and 0.35 s; compare the base at
  // 0.5 s with the unpushed episode (the PD law reacts, but not within 0.15 s).
  const auto displacement = [&](const char* direction) {
    EnvOptions options = {{"push_force", "30"},
                          {"push_force_min", "30"},
                          {"push_start", "0.25"},
                          {"push_interval", "0.2"},
                          {"push_direction", direction}};
    const Trace pushed = pd_trace(id(), options, 3, 100);
    const Trace nominal = pd_trace(id(), {}, 3, 100);
    return Eigen::Vector3d(pushed.base_positions.back() - nominal.base_positions.back());
  };
  const Eigen::Vector3d forward = displacement("forward");
  const Eigen::Vector3d backward = displacement("backward");
  const Eigen::Vector3d lateral = displacement("lateral");
  EXPECT_GT(forward.x(), 0.01);
  EXPECT_LT(std::abs(forward.y()), 0.2 * forward.x());
  EXPECT_LT(backward.x(), -0.01);
  EXPECT_GT(std::abs(lateral.y()), 0.01);
  EXPECT_LT(std::abs(lateral.x()), 0.5 * std::abs(lateral.y()));
}

TEST_P(EnginePerturbations, ObservationNoiseStaysInBoundsAndOffTheReward) {
  const Trace nominal = pd_trace(id(), {}, 3, 1);
  auto env = make_env(id(), {{"observation_noise", "0.01"}});
  std::vector<float> observation(4);
  env->reset(3, observation);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_LE(std::abs(observation[i] - nominal.observations[0][i]), 0.01f + 1e-6f);
  }
  EXPECT_NE(observation, nominal.observations[0]);
  // The same actions as the nominal episode: the rewards come from the true state.
  std::vector<float> action = {pd(nominal.observations[0], 0)};
  const StepResult result = env->step(action, observation);
  EXPECT_EQ(result.reward, nominal.rewards[0]);
}

TEST_P(EnginePerturbations, ActionDelayAppliesEachCommandStepsLater) {
  // Servo commands (the wheels' velocities along a sequence, the rest neutral); with a delay
  // of 3 the servos apply c0 (the episode's first command, held since before the start),
  // c0, c0, c0, c1...
  const auto wheel_velocity = [](int step) {
    return 3.0f * std::sin(0.05f * static_cast<float>(step + 1));
  };
  const auto servo_run = [](Env& env, const std::function<float(int)>& velocity) {
    std::vector<float> observation(env.observation_space().size());
    std::vector<float> action(env.action_space().size());
    env.neutral_action(action);
    env.reset(1, observation);
    std::vector<std::vector<float>> trace;
    for (int step = 0; step < 60; ++step) {
      action[kLeftWheel * kServoCommandFields.size() + 1] = velocity(step);
      action[kRightWheel * kServoCommandFields.size() + 1] = -velocity(step);
      env.step(action, observation);
      trace.push_back(observation);
    }
    return trace;
  };
  auto delayed = make_env(id("Servos"), {{"action_delay", "3"}});
  auto plain = make_env(id("Servos"), {});
  const auto delayed_run = servo_run(*delayed, wheel_velocity);
  EXPECT_EQ(delayed_run, servo_run(*plain, [&](int step) {
              return step < 3 ? wheel_velocity(0) : wheel_velocity(step - 3);
            }));
  // The same delay in seconds: 15 ms at the servos environment's 5 ms steps (16 ms rounds
  // to it too).
  ASSERT_EQ(delayed->timestep(), 0.005);
  auto in_seconds = make_env(id("Servos"), {{"action_delay_time", "0.016"}});
  EXPECT_EQ(servo_run(*in_seconds, wheel_velocity), delayed_run);
}

TEST_P(EnginePerturbations, ActionLagAppliesTheFiltersMeanOverEachStep) {
  // The pendulum's action is the ground velocity, which its servos get as wheel velocities
  // in proportion: the servo-side filter is the same filter on the action.
  const auto sequence = [](const std::vector<float>&, int step) {
    return step < 20 ? 0.5f : -0.2f;
  };
  auto lagged = make_env(id(), {{"action_lag_min", "0.01"}, {"action_lag_max", "0.01"}});
  const Trace actual = run(*lagged, 1, 60, sequence);
  auto plain = make_env(id(), {});
  const double dt = plain->timestep();  // 5 ms: the lag is two steps
  const double state_gain = 1.0 - std::exp(-dt / 0.01);
  const double applied_gain = 1.0 - (0.01 / dt) * state_gain;
  double filtered = 0.5;  // the episode's first command
  const Trace expected = run(*plain, 1, 60, [&](const std::vector<float>& o, int step) {
    const double gap = sequence(o, step) - filtered;
    const double applied = filtered + applied_gain * gap;
    filtered += state_gain * gap;
    return static_cast<float>(applied);
  });
  ASSERT_EQ(actual.observations.size(), expected.observations.size());
  double largest = 0.0;
  for (std::size_t t = 0; t < actual.observations.size(); ++t) {
    for (std::size_t i = 0; i < actual.observations[t].size(); ++i) {
      largest = std::max(largest, static_cast<double>(std::abs(actual.observations[t][i] -
                                                               expected.observations[t][i])));
    }
  }
  EXPECT_LT(largest, 1e-4);  // float rounding of the action on one side only
  // And it lags: the same run without it differs by far more.
  const Trace unlagged = run(*plain, 1, 60, sequence);
  EXPECT_GT(std::abs(unlagged.observations[25][3] - actual.observations[25][3]), 1e-2);
}

TEST_P(EnginePerturbations, AResidualPolicysBaseControllerPassesTheDelayLikeTheBaseline) {
  // A zero residual on the base controller is the baseline controller, and the servos'
  // delay and lag must treat both alike (they lagged the agent's residual only, before).
  const std::string balancer = testing::kVelocityBaseline;
  const EnvOptions actuation = {
      {"action_delay", "2"}, {"action_lag_max", "0.03"}, {"action_lag_min", "0.03"}};
  EnvOptions residual_options = actuation;
  residual_options.emplace_back("base_controller", balancer);
  auto residual = make_env(id("Velocity"), residual_options);
  auto baseline = make_env(id("Velocity"), actuation);
  std::unique_ptr<Controller> controller = make_builtin_controller(balancer, *baseline);
  std::vector<float> residual_observation(residual->observation_space().size());
  std::vector<float> baseline_observation(baseline->observation_space().size());
  std::vector<float> zero(residual->action_space().size(), 0.0f);
  std::vector<float> action(baseline->action_space().size(), 0.0f);
  residual->reset(5, residual_observation);
  baseline->reset(5, baseline_observation);
  controller->reset();
  for (int step = 0; step < 100; ++step) {
    controller->act(baseline_observation, action);
    baseline->step(action, baseline_observation);
    residual->step(zero, residual_observation);
    ASSERT_EQ(residual->full_observation()->sim_base.position,
              baseline->full_observation()->sim_base.position)
        << "step " << step;
  }
  // And the delay is felt: without it the robot is elsewhere.
  auto prompt = make_env(id("Velocity"), {{"base_controller", balancer}});
  prompt->reset(5, residual_observation);
  for (int step = 0; step < 100; ++step) prompt->step(zero, residual_observation);
  EXPECT_NE(prompt->full_observation()->sim_base.position,
            residual->full_observation()->sim_base.position);
}

TEST_P(EnginePerturbations, InconsistentSettingsAreRefusedWithTheirNames) {
  const auto message = [&](const EnvOptions& options) {
    try {
      make_env(id(), options);
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string();
  };
  EXPECT_NE(message({{"push_force", "10"}, {"push_force_min", "20"}}).find("push_force_min"),
            std::string::npos);
  EXPECT_NE(message({{"push_force", "10"}, {"push_duration", "2"}}).find("push_interval"),
            std::string::npos);
  EXPECT_NE(message({{"action_lag_min", "0.2"}, {"action_lag_max", "0.1"}}).find("action_lag"),
            std::string::npos);
  EXPECT_NE(message({{"inertia_variation", "1.5"}}).find("outside [0, 0.99]"), std::string::npos);
  EXPECT_NE(message({{"push_direction", "up"}}).find("not one of"), std::string::npos);
  EXPECT_NE(message({{"push_force", "10"}, {"push_sagittal_share", "0.5"}})
                .find("push_sagittal_share applies to push_direction any"),
            std::string::npos);
  EXPECT_NE(message({{"push_sagittal_share", "1.5"}}).find("push_sagittal_share"),
            std::string::npos);
}

TEST_P(EnginePerturbations, OnASlopeThePolicyReadsThePitchOfARealSlope) {
  // The pendulum starts upright on the floor: facing up an 8 deg slope, it leans 8 deg
  // back from the vertical, which its first observation (the IMU's pitch) reads.
  auto env = make_env(id(), {{"slope_pitch", "8"}});
  std::vector<float> observation(4);
  env->reset(3, observation);
  EXPECT_NEAR(observation[0], -8.0 * M_PI / 180.0, 1e-6);
  EXPECT_NEAR(env->full_observation()->base_orientation.pitch, -8.0 * M_PI / 180.0, 1e-12);
  // Upright in the floor's frame, the ground truth.
  EXPECT_TRUE(env->full_observation()->sim_base.orientation.isApprox(Eigen::Quaterniond::Identity(),
                                                                     1e-12));
  // So the velocity task measures 8 deg from gravity and none from the floor.
  EXPECT_NEAR(VelocityTask::tilt(*env->full_observation()), 8.0 * M_PI / 180.0, 1e-6);
  EXPECT_NEAR(VelocityTask::floor_tilt(*env->full_observation()), 0.0, 1e-6);
}

TEST_P(EnginePerturbations, APayloadChangesTheEpisode) {
  const Trace nominal = pd_trace(id(), {}, 3, 100);
  const Trace loaded = pd_trace(id(), {{"payload_mass", "2"}, {"payload_offset_x", "0.1"}}, 3, 100);
  // The same start, to rounding (Bullet places the base by its centre of mass, which the
  // payload moves), then another episode.
  for (std::size_t i = 0; i < nominal.observations.front().size(); ++i) {
    EXPECT_NEAR(nominal.observations.front()[i], loaded.observations.front()[i], 1e-6f) << i;
  }
  EXPECT_GT(std::abs(nominal.observations.back()[0] - loaded.observations.back()[0]), 1e-3f);
}

TEST_P(EnginePerturbations, BadSlopesAndPayloadsAreRefusedWithTheirNames) {
  const auto message = [&](const EnvOptions& options) {
    try {
      make_env(id(), options);
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string();
  };
  for (const auto& [name, value] :
       std::vector<std::pair<std::string, std::string>>{{"slope_pitch", "15.5"},
                                                        {"slope_roll", "-20"},
                                                        {"slope_pitch", "nan"},
                                                        {"payload_mass", "-0.5"},
                                                        {"payload_mass", "3.1"},
                                                        {"payload_mass", "nan"},
                                                        {"payload_offset_x", "0.25"},
                                                        {"payload_offset_y", "-inf"},
                                                        {"payload_offset_z", "nan"}}) {
    EXPECT_NE(message({{name, value}}).find(name), std::string::npos) << name << "=" << value;
  }
  EXPECT_EQ(message({{"slope_pitch", "-15"},
                     {"slope_roll", "15"},
                     {"payload_mass", "3"},
                     {"payload_offset_x", "0.2"},
                     {"payload_offset_y", "-0.2"}}),
            "");
}

TEST_P(EnginePerturbations, EveryKindTakesThem) {
  for (const char* kind : {"Servos", "Gyropod", "ServosTask"}) {
    auto env = make_env(id(kind), kEverythingOn);
    std::vector<float> observation(env->observation_space().size());
    std::vector<float> action(env->action_space().size());
    env->reset(0, observation);
    env->neutral_action(action);
    for (int step = 0; step < 50; ++step) env->step(action, observation);
    for (float value : observation) EXPECT_TRUE(std::isfinite(value)) << kind;
  }
}

INSTANTIATE_TEST_SUITE_P(Engines, EnginePerturbations, ::testing::Values("Bullet", "MuJoCo"));

TEST(Perturbations, SlopesAndPayloadsAreFixedAndDrawNothing) {
  // The same generator state with and without them: every randomised value, and what the
  // generator draws next, stay the same, so that a seed gives the same episode otherwise.
  PerturbationSettings randomised;
  randomised.inertia_variation = 0.2;
  randomised.joint_friction = 0.01;
  randomised.imu_gyroscope_bias = 0.01;
  randomised.floor_friction_variation = 0.3;
  PerturbationSettings fixed = randomised;
  fixed.slope_pitch = 8.0;
  fixed.slope_roll = -5.0;
  fixed.payload_mass = 2.5;
  fixed.payload_offset_x = 0.1;
  fixed.payload_offset_y = -0.2;
  fixed.payload_offset_z = 0.05;
  fixed.joint_friction_fixed = 0.02;
  fixed.wheel_servo_gain_scale = 1.5;
  fixed.leg_servo_gain_scale = 0.7;
  fixed.imu_gyroscope_bias_fixed = Eigen::Vector3d(0.0, 0.03, 0.0);
  EXPECT_TRUE(fixed.any());
  std::mt19937_64 first(9);
  std::mt19937_64 second(9);
  const PhysicsVariation a = randomised.sample(first, 1.0);
  const PhysicsVariation b = fixed.sample(second, 1.0);
  EXPECT_EQ(a.mass_scale, b.mass_scale);
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {  // drawn + fixed
    EXPECT_DOUBLE_EQ(b.joint_friction[servo], a.joint_friction[servo] + 0.02);
    EXPECT_EQ(b.servo_gain_scale[servo], is_wheel(servo) ? 1.5 : 0.7);
    EXPECT_EQ(a.servo_gain_scale[servo], 1.0);
  }
  EXPECT_DOUBLE_EQ(b.imu.gyroscope_bias.y(), a.imu.gyroscope_bias.y() + 0.03);
  EXPECT_EQ(b.imu.gyroscope_bias.x(), a.imu.gyroscope_bias.x());
  EXPECT_EQ(a.floor_friction_scale, b.floor_friction_scale);
  EXPECT_EQ(a.noise_seed, b.noise_seed);
  EXPECT_EQ(first(), second());
  // The fixed values, in the variation's units (radians), whatever the curriculum scale.
  const PhysicsVariation unscaled = fixed.sample(second, 0.0);
  EXPECT_DOUBLE_EQ(unscaled.slope_pitch, 8.0 * M_PI / 180.0);
  EXPECT_DOUBLE_EQ(unscaled.slope_roll, -5.0 * M_PI / 180.0);
  EXPECT_EQ(unscaled.payload_mass, 2.5);
  EXPECT_EQ(unscaled.payload_offset, Eigen::Vector3d(0.1, -0.2, 0.05));
}

TEST(Perturbations, RandomisedWorldsStayInTheirBoundsAndLeaveTheOtherDrawsAlone) {
  PerturbationSettings plain;
  plain.inertia_variation = 0.1;
  PerturbationSettings worlds = plain;
  worlds.slope_variation = 10.0;
  worlds.payload_mass_variation = 1.6;
  worlds.payload_offset_variation = 0.1;
  worlds.payload_offset_z = 0.1;
  worlds.torque_limit_variation = 0.25;
  EXPECT_TRUE(worlds.any());
  const double max_slope = 10.0 * M_PI / 180.0;
  std::vector<double> slopes;
  for (std::uint64_t seed = 0; seed < 50; ++seed) {
    std::mt19937_64 first(seed);
    std::mt19937_64 second(seed);
    const PhysicsVariation a = plain.sample(first, 1.0);
    const PhysicsVariation b = worlds.sample(second, 1.0);
    // The other draws, and what the generator gives next, are those without the options.
    EXPECT_EQ(a.mass_scale, b.mass_scale);
    EXPECT_EQ(a.noise_seed, b.noise_seed);
    EXPECT_EQ(first(), second());
    EXPECT_LE(std::abs(b.slope_pitch), max_slope);
    EXPECT_LE(std::abs(b.slope_roll), max_slope);
    EXPECT_GE(b.payload_mass, 0.0);
    EXPECT_LE(b.payload_mass, 1.6);
    EXPECT_LE(std::abs(b.payload_offset.x()), 0.1);
    EXPECT_LE(std::abs(b.payload_offset.y()), 0.1);
    EXPECT_EQ(b.payload_offset.z(), 0.1);
    EXPECT_GE(b.torque_limit_scale, 0.75);
    EXPECT_LE(b.torque_limit_scale, 1.0);
    EXPECT_NO_THROW(b.validate());
    slopes.push_back(b.slope_pitch);
  }
  // Drawn, not fixed: the 50 episodes spread over most of the range.
  const auto [low, high] = std::minmax_element(slopes.begin(), slopes.end());
  EXPECT_LT(*low, -0.5 * max_slope);
  EXPECT_GT(*high, 0.5 * max_slope);
  // The curriculum at 0 leaves the fixed values alone; a fixed slope near the largest
  // one plus its variation stays within the largest slope.
  std::mt19937_64 generator(3);
  const PhysicsVariation start = worlds.sample(generator, 0.0);
  EXPECT_EQ(start.slope_pitch, 0.0);
  EXPECT_EQ(start.payload_mass, 0.0);
  EXPECT_EQ(start.torque_limit_scale, 1.0);
  worlds.slope_pitch = kMaxSlopeDegrees;
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    std::mt19937_64 draws(seed);
    EXPECT_LE(worlds.sample(draws, 1.0).slope_pitch, kMaxSlopeDegrees * M_PI / 180.0);
  }
}

TEST(Perturbations, BumpShareLaysTheBumpsInThatShareOfEpisodesAndLeavesTheOtherDrawsAlone) {
  PerturbationSettings always;
  always.inertia_variation = 0.1;
  always.slope_variation = 10.0;
  PerturbationSettings quarter = always;
  quarter.bump_share = 0.25;
  EXPECT_TRUE(quarter.any());
  int with_bumps = 0;
  int with_bumps_at_curriculum_start = 0;
  for (std::uint64_t seed = 0; seed < 400; ++seed) {
    std::mt19937_64 plain_draws(seed);
    std::mt19937_64 shared_draws(seed);
    const PhysicsVariation a = always.sample(plain_draws, 1.0);
    const PhysicsVariation b = quarter.sample(shared_draws, 1.0);
    EXPECT_TRUE(a.floor_bumps);
    // Drawn last, in the randomised world's stream: every other draw is the same.
    EXPECT_EQ(a.mass_scale, b.mass_scale);
    EXPECT_EQ(a.slope_pitch, b.slope_pitch);
    EXPECT_EQ(plain_draws(), shared_draws());
    with_bumps += b.floor_bumps ? 1 : 0;
    std::mt19937_64 start_draws(seed);
    with_bumps_at_curriculum_start += quarter.sample(start_draws, 0.0).floor_bumps ? 1 : 0;
  }
  // 100 of 400 expected (the binomial's standard deviation is 8.7), at any curriculum scale.
  EXPECT_GT(with_bumps, 70);
  EXPECT_LT(with_bumps, 130);
  EXPECT_EQ(with_bumps_at_curriculum_start, with_bumps);
  PerturbationSettings never;
  never.bump_share = 0.0;
  std::mt19937_64 generator(1);
  const PhysicsVariation flat = never.sample(generator, 1.0);
  EXPECT_FALSE(flat.floor_bumps);
  EXPECT_TRUE(flat.changes_model());
}

TEST(Perturbations, OnlyPhysicsBackendsOfferPhysicalOnes) {
  EXPECT_THROW(make_env("Upkie-Mock-Pendulum", {{"push_force", "10"}}), std::invalid_argument);
  EXPECT_THROW(make_env("Upkie-Mock-Pendulum", {{"slope_pitch", "5"}}), std::invalid_argument);
  EXPECT_THROW(make_env("Upkie-Mock-Pendulum", {{"payload_mass", "1"}}), std::invalid_argument);
  // Observation noise and action lag are wrappers: every backend has them.
  EXPECT_NO_THROW(make_env("Upkie-Mock-Pendulum", {{"observation_noise", "0.1"}}));
}

TEST(Perturbations, TaskOptionsDropRandomisationAndOptionsTheTargetLacks) {
  const EnvOptions trained = {{"frequency", "200"},          {"observe_pitch", "true"},
                              {"init_rand_pitch", "0.1"},    {"push_force", "20"},
                              {"observation_noise", "0.01"}, {"fall_pitch", "0.8"}};
  const EnvOptions kept =
      task_options("Upkie-MuJoCo-ServosTask", trained, "Upkie-Bullet-ServosTask");
  const EnvOptions expected = {
      {"frequency", "200"}, {"observe_pitch", "true"}, {"fall_pitch", "0.8"}};
  EXPECT_EQ(kept, expected);
  // A pendulum has no observe_pitch: it is left out, not an error.
  const EnvOptions pendulum =
      task_options("Upkie-MuJoCo-ServosTask", trained, "Upkie-Mock-Pendulum");
  const EnvOptions pendulum_expected = {{"frequency", "200"}, {"fall_pitch", "0.8"}};
  EXPECT_EQ(pendulum, pendulum_expected);
}

TEST(Perturbations, TaskOptionsLeaveTheTrainingsPhysicsStepOut) {
  // A policy trained at 5 ms for speed is rolled out at the 1 ms reference.
  const EnvOptions trained = {{"nb_substeps", "4"}, {"residual_scale", "1"}};
  const EnvOptions expected = {{"residual_scale", "1"}};
  EXPECT_EQ(task_options("Upkie-MuJoCo-Velocity", trained, "Upkie-MuJoCo-Velocity"), expected);
  EXPECT_EQ(task_options("Upkie-MuJoCo-Velocity", trained, "Upkie-Bullet-Velocity"), expected);
}

/// Every servo at wheel-like velocity `velocity` and leg-like position `position`.
ServoAction servo_command(double velocity, double position = 0.0) {
  ServoAction action{};
  for (ServoCommand& servo : action) {
    servo.velocity = velocity;
    servo.position = position;
  }
  return action;
}

TEST(ActionLag, RefusesANonFiniteCommandWhenSentNotWhenItLeavesTheDelay) {
  auto env = make_env("Upkie-Mock-Servos", {{"action_delay", "5"}});
  Env* inner = env.get();
  while (auto* wrapper = dynamic_cast<EnvWrapper*>(inner)) inner = &wrapper->inner();
  auto& servos = dynamic_cast<ServosEnv&>(*inner);
  std::vector<float> observation(env->observation_space().size());
  env->reset(0, observation);
  ServoAction command = servo_command(0.0);
  command[kLeftWheel].velocity = std::nan("");
  try {
    servos.step_servos(command);
    FAIL() << "a NaN velocity passed";
  } catch (const InvalidCommandError& error) {
    EXPECT_NE(std::string(error.what()).find("left_wheel"), std::string::npos);
  }
}

TEST(ActionLag, DrawsTheDelayPerEpisodeAndActsAsThatFixedDelay) {
  ActionLagSettings settings;
  settings.delay_steps = 1;
  settings.delay_steps_max = 3;
  ActionLag drawn(settings, 0.02);
  std::set<int> delays;
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    drawn.reset(seed, 1.0);
    ASSERT_GE(drawn.delay(), 1);
    ASSERT_LE(drawn.delay(), 3);
    delays.insert(drawn.delay());
    for (int step = 0; step < 8; ++step) {
      // The command sent `delay` steps ago, or the episode's first before it.
      const int sent_at = std::max(0, step - drawn.delay());
      const double applied = drawn.apply(servo_command(0.1 * step))[kRightKnee].velocity;
      ASSERT_EQ(applied, 0.1 * sent_at) << "seed " << seed << ", step " << step;
    }
  }
  EXPECT_EQ(delays, (std::set<int>{1, 2, 3}));
}

TEST(ActionLag, TheStepsMeanMatchesFilteringAtEveryMillisecond) {
  // A 10 ms lag at 50 Hz: the former per-step law (dt/τ clipped at 1) applied no lag at
  // all; the mean over the step is what a servo filtering continuously applies on average.
  ActionLagSettings settings;
  settings.time_constant_min = settings.time_constant_max = 0.01;
  ActionLag lag(settings, 0.02);
  lag.reset(0, 1.0);
  lag.apply(servo_command(0.0));
  ServoAction state = servo_command(0.0);
  ServoAction applied_fine{};
  const ServoTargetLag fine = ServoTargetLag::step_end(0.01, 0.001);
  for (int step = 1; step <= 5; ++step) {
    double mean = 0.0;
    for (int ms = 0; ms < 20; ++ms) {
      fine.step(servo_command(1.0, 0.3), state, applied_fine);
      mean += applied_fine[kLeftWheel].velocity / 20.0;
    }
    const ServoAction& applied = lag.apply(servo_command(1.0, 0.3));
    EXPECT_NEAR(applied[kLeftWheel].velocity, mean, 0.03) << "step " << step;
    if (step == 1) {
      EXPECT_LT(applied[kLeftWheel].velocity, 0.65);  // half a step behind, not at 1
      EXPECT_GT(applied[kLeftWheel].velocity, 0.5);
    }
  }
}

TEST(ActionLag, ANanPositionPassesAndGainsAreNotFiltered) {
  ActionLagSettings settings;
  settings.time_constant_min = settings.time_constant_max = 0.05;
  ActionLag lag(settings, 0.02);
  lag.reset(0, 1.0);
  ServoAction first = servo_command(0.0, std::nan(""));
  lag.apply(first);
  ServoAction next = servo_command(1.0, 0.4);
  next[kRightHip].kp_scale = 0.5;
  const ServoAction& applied = lag.apply(next);
  EXPECT_EQ(applied[kLeftWheel].position, 0.4);  // from no position loop: the target at once
  EXPECT_LT(applied[kLeftWheel].velocity, 0.5);  // filtered
  EXPECT_EQ(applied[kRightHip].kp_scale, 0.5);   // as sent
}

TEST(ResidualLag, DrawsItsTimeConstantPerEpisodeAndFiltersFromZero) {
  ResidualLag lag(0.0, 0.08, 0.02, 2);
  std::set<double> drawn;
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    lag.reset(seed, 1.0);
    ASSERT_GE(lag.time_constant(), 0.0);
    ASSERT_LE(lag.time_constant(), 0.08);
    drawn.insert(lag.time_constant());
  }
  EXPECT_EQ(drawn.size(), 20u);
  lag.reset(3, 0.5);  // the curriculum halves the range
  EXPECT_LE(lag.time_constant(), 0.04);
  const ServoTargetLag law = ServoTargetLag::step_mean(lag.time_constant(), 0.02);
  std::array<float, 2> action = {1.0f, -0.5f};
  lag.apply(action);
  EXPECT_NEAR(action[0], law.applied_gain, 1e-6);  // from 0 toward 1
  EXPECT_NEAR(action[1], -0.5 * law.applied_gain, 1e-6);
  EXPECT_LT(action[0], 1.0f);
}

TEST_P(EnginePerturbations, TheResidualLagLagsThePolicysShareNotTheBase) {
  const std::string balancer = testing::kVelocityBaseline;
  const auto base_position = [&](const EnvOptions& options, float residual) {
    auto env = make_env(id("Velocity"), options);
    std::vector<float> observation(env->observation_space().size());
    std::vector<float> action(env->action_space().size(), residual);
    env->reset(2, observation);
    for (int step = 0; step < 50; ++step) env->step(action, observation);
    return env->full_observation()->sim_base.position;
  };
  const EnvOptions plain = {{"base_controller", balancer}, {"residual_scale", "0.3"}};
  EnvOptions lagged = plain;
  lagged.emplace_back("residual_lag_max", "0.08");
  // A zero residual: the base alone acts, unlagged, the same either way.
  EXPECT_EQ(base_position(plain, 0.0f), base_position(lagged, 0.0f));
  // A residual: lagged, it moves the robot otherwise.
  EXPECT_NE(base_position(plain, 0.5f), base_position(lagged, 0.5f));
  // The nominal filter acts on the residual alone too, evaluations included.
  EnvOptions filtered = plain;
  filtered.emplace_back("residual_filter", "0.04");
  EXPECT_EQ(base_position(plain, 0.0f), base_position(filtered, 0.0f));
  EXPECT_NE(base_position(plain, 0.5f), base_position(filtered, 0.5f));
  // Without a base there is no residual to lag: refused, naming the option.
  const auto refusal = [&](const char* option, const char* value) {
    return testing::error_message([&] { make_env(id("Velocity"), {{option, value}}); });
  };
  EXPECT_NE(refusal("residual_lag_max", "0.08").find("residual_lag_max needs a base_controller"),
            std::string::npos);
  EXPECT_NE(refusal("residual_filter", "0.04").find("residual_filter needs a base_controller"),
            std::string::npos);
  // A deployed filter the training's draw never reached is refused, naming both.
  EnvOptions outside = plain;
  outside.emplace_back("residual_filter", "0.1");
  outside.emplace_back("residual_lag_max", "0.08");
  try {
    make_env(id("Velocity"), outside);
    ADD_FAILURE() << "a filter outside the drawn range was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("residual_filter 0.1"), std::string::npos);
    EXPECT_NE(std::string(error.what()).find("residual_lag_max"), std::string::npos);
  }
}

TEST_P(EnginePerturbations, TheResidualFadesWithTheTiltLeavingTheBaseAlone) {
  // Facing up a 15 deg slope the robot starts 0.26 rad from gravity, as the IMU reads it.
  const std::string balancer = testing::kVelocityBaseline;
  double tilt = 0.0;
  // The left hip's command sent in the first step (the observation's last action).
  const auto sent_hip = [&](const EnvOptions& fade, float residual) {
    EnvOptions options = {
        {"base_controller", balancer}, {"residual_scale", "0.3"}, {"slope_pitch", "15"}};
    options.insert(options.end(), fade.begin(), fade.end());
    auto env = make_env(id("Velocity"), options);
    std::vector<float> observation(env->observation_space().size());
    std::vector<float> action(env->action_space().size(), 0.0f);
    env->reset(2, observation);
    tilt = VelocityTask::tilt(*env->full_observation());
    action[kLeftHip] = residual;
    env->step(action, observation);
    const std::size_t last_action = 12;  // after 4 legs, 2 wheels, gravity and gyroscope
    return observation[last_action + kLeftHip];
  };
  // The agent's share of the hip command: (sent with 0.5 - sent with 0) / (0.3 x 0.5).
  const auto share = [&](const EnvOptions& fade) {
    return (sent_hip(fade, 0.5f) - sent_hip(fade, 0.0f)) / 0.15;
  };
  EXPECT_NEAR(share({}), 1.0, 1e-5);
  ASSERT_NEAR(tilt, 15.0 * M_PI / 180.0, 0.01);
  // Past the fade's end the base acts alone; within it the share falls linearly.
  EXPECT_EQ(sent_hip({{"residual_fade_start", "0.1"}, {"residual_fade_end", "0.2"}}, 0.5f),
            sent_hip({{"residual_fade_start", "0.1"}, {"residual_fade_end", "0.2"}}, 0.0f));
  EXPECT_NEAR(share({{"residual_fade_start", "0.2"}, {"residual_fade_end", "0.3"}}),
              (0.3 - tilt) / 0.1, 1e-4);
  EXPECT_NEAR(share({{"residual_fade_start", "0.3"}, {"residual_fade_end", "0.4"}}), 1.0, 1e-5);
  // A fade needs a base controller and a start below its end, and says so.
  const auto message = [&](const EnvOptions& options) {
    return testing::error_message([&] { make_env(id("Velocity"), options); });
  };
  EXPECT_NE(
      message({{"residual_fade_end", "0.3"}}).find("residual_fade_end needs a base_controller"),
      std::string::npos);
  EXPECT_NE(message({{"base_controller", balancer},
                     {"residual_fade_start", "0.3"},
                     {"residual_fade_end", "0.3"}})
                .find("residual_fade_start 0.3"),
            std::string::npos);
}

TEST_P(EnginePerturbations, TheLegsShareOfTheResidualIsItsGainTimesTheWheels) {
  // The command sent to `servo` in the first step (the observation's last action) when the
  // agent asks `residual` of it alone.
  const auto sent = [&](const std::string& leg_gain, std::size_t servo, float residual) {
    auto env = make_env(id("Velocity"), {{"base_controller", testing::kVelocityBaseline},
                                         {"residual_scale", "0.3"},
                                         {"residual_leg_gain", leg_gain}});
    std::vector<float> observation(env->observation_space().size());
    std::vector<float> action(env->action_space().size(), 0.0f);
    env->reset(2, observation);
    action[servo] = residual;
    env->step(action, observation);
    const std::size_t last_action = 12;  // after 4 legs, 2 wheels, gravity and gyroscope
    return observation[last_action + servo];
  };
  // The agent's share of a command: (sent with 0.5 - sent with 0) / (0.3 x 0.5).
  const auto share = [&](const std::string& leg_gain, std::size_t servo) {
    return (sent(leg_gain, servo, 0.5f) - sent(leg_gain, servo, 0.0f)) / 0.15;
  };
  EXPECT_NEAR(share("1", kLeftHip), 1.0, 1e-5);
  EXPECT_NEAR(share("3", kLeftHip), 3.0, 1e-5);
  EXPECT_NEAR(share("3", kRightKnee), 3.0, 1e-5);
  EXPECT_NEAR(share("0", kLeftHip), 0.0, 1e-6);
  // The wheels keep residual_scale whatever the legs' gain.
  EXPECT_NEAR(share("3", kLeftWheel), 1.0, 1e-5);
  EXPECT_NEAR(share("0", kRightWheel), 1.0, 1e-5);
  // Without a base controller there is no residual to weigh: refused, naming the option.
  EXPECT_NE(testing::error_message([&] {
              make_env(id("Velocity"), {{"residual_leg_gain", "3"}});
            }).find("residual_leg_gain needs a base_controller"),
            std::string::npos);
}

TEST(ResidualLag, WithoutADrawFiltersWithTheNominalTimeConstant) {
  ResidualLag lag(0.04, 0.0, 0.02, 1);
  for (std::uint64_t seed = 0; seed < 5; ++seed) {
    lag.reset(seed, 1.0);
    EXPECT_EQ(lag.time_constant(), 0.04);
  }
  const ServoTargetLag law = ServoTargetLag::step_mean(0.04, 0.02);
  std::array<float, 1> action = {1.0f};
  lag.apply(action);
  EXPECT_NEAR(action[0], law.applied_gain, 1e-6);
  EXPECT_LT(action[0], 0.7f);  // a 40 ms filter at 50 Hz passes well under a step's worth
}

TEST(ResidualLag, RefusesANegativeOrNonFiniteTimeConstantNamingTheOption) {
  const auto message = [](double nominal, double draw) {
    try {
      ResidualLag(nominal, draw, 0.02, 1);
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string();
  };
  EXPECT_NE(message(-0.01, 0.0).find("residual_filter"), std::string::npos);
  EXPECT_NE(message(0.0, std::nan("")).find("residual_lag_max"), std::string::npos);
}

TEST(ResidualLag, TheDrawStaysInTrainingTheFilterEverywhere) {
  const EnvOptions trained = {
      {"residual_lag_max", "0.08"}, {"residual_filter", "0.04"}, {"residual_scale", "0.3"}};
  const EnvOptions expected = {{"residual_filter", "0.04"}, {"residual_scale", "0.3"}};
  EXPECT_EQ(task_options("Upkie-MuJoCo-Velocity", trained, "Upkie-MuJoCo-Velocity"), expected);
}

TEST(ActionLag, RefusesADelayMaximumOutOfRangeNamingIt) {
  ActionLagSettings settings;
  settings.delay_steps_max = -1;
  EXPECT_NE(settings.problem().find("action_delay_max"), std::string::npos);
}

// A delay in seconds is the same time at any agent rate, in whole steps.
TEST(ActionLag, ADelayInSecondsIsWholeStepsAtAnyRate) {
  ActionLagSettings settings;
  settings.delay_time = 0.02;
  ASSERT_TRUE(settings.any());
  ASSERT_EQ(settings.problem(), "");
  for (const auto& [step, steps] : {std::pair{0.02, 1}, {0.01, 2}, {0.005, 4}, {0.03, 1}}) {
    ActionLag lag(settings, step);
    lag.reset(0, 1.0);
    EXPECT_EQ(lag.delay(), steps) << "a step of " << step << " s";
  }
  ActionLag halved(settings, 0.01);
  halved.reset(0, 0.5);  // the randomisation scale scales it as a delay in steps
  EXPECT_EQ(halved.delay(), 1);
}

TEST(ActionLag, RefusesADelayInSecondsAndStepsOrOutOfRangeNamingIt) {
  ActionLagSettings both;
  both.delay_time = 0.02;
  both.delay_steps = 1;
  EXPECT_NE(both.problem().find("action_delay_time and action_delay"), std::string::npos);
  both.delay_steps = 0;
  both.delay_steps_max = 2;
  EXPECT_NE(both.problem().find("action_delay_time"), std::string::npos);
  for (const double bad : {-0.01, 1.5, std::nan(""), HUGE_VAL}) {
    ActionLagSettings settings;
    settings.delay_time = bad;
    EXPECT_NE(settings.problem().find("action_delay_time must be in [0, 1"), std::string::npos)
        << bad;
    EXPECT_THROW(ActionLag(settings, 0.02), std::invalid_argument) << bad;
  }
  ActionLagSettings long_delay;
  long_delay.delay_time = 1.0;
  try {
    ActionLag lag(long_delay, 1e-6);
    FAIL() << "a million steps of delay passed";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("more than 10000 steps"), std::string::npos);
  }
}

}  // namespace
}  // namespace upkie_rl
