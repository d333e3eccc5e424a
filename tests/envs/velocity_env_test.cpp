#include "envs/kinds/velocity_env.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

#include "common/error_message.hpp"
#include "envs/registry/env_factory.hpp"
#include "envs/registry/registry.hpp"
#include "envs/scripted_simulation.hpp"
#include "envs/tasks/velocity_command_sampler.hpp"
#include "envs/tasks/velocity_reward.hpp"
#include "envs/tasks/velocity_task.hpp"

namespace upkie_rl {
namespace {

/// An observation of the default task (with the height command).
using Obs = std::array<float, VelocityTask::kHeightObservationSize>;
/// An observation of the task without the height command.
using LegacyObs = std::array<float, VelocityTask::kObservationSize>;
using Act = std::array<float, VelocityTask::kActionSize>;

using testing::error_message;

TEST(VelocityCommandSampler, DrawsWithinTheRangesWithAShareOfZeroCommands) {
  VelocityCommandRanges ranges;
  ranges.max_forward_velocity = 0.8;
  ranges.max_yaw_rate = 1.2;
  ranges.zero_command_probability = 0.25;
  ranges.resample_time_min = 1.0;
  ranges.resample_time_max = 2.0;
  VelocityCommandSampler sampler(ranges);
  const std::uint64_t seed = 3;
  sampler.reset(&seed);
  int draws = 1;
  int zeros = 0;
  double since_draw = 0.0;
  double max_forward = 0.0;
  constexpr double kDt = 0.02;
  for (int step = 0; step < 200000; ++step) {
    since_draw += kDt;
    if (!sampler.advance(kDt)) continue;
    EXPECT_GE(since_draw, 1.0 - 1e-9);
    EXPECT_LE(since_draw, 2.0 + kDt + 1e-9);
    since_draw = 0.0;
    ++draws;
    const VelocityCommand& command = sampler.command();
    EXPECT_LE(std::abs(command.forward_velocity), 0.8);
    EXPECT_LE(std::abs(command.yaw_rate), 1.2);
    max_forward = std::max(max_forward, std::abs(command.forward_velocity));
    if (command.forward_velocity == 0.0 && command.yaw_rate == 0.0) ++zeros;
  }
  EXPECT_GT(draws, 2000);
  EXPECT_NEAR(static_cast<double>(zeros) / draws, 0.25, 0.03);
  EXPECT_GT(max_forward, 0.75);
}

TEST(VelocityCommandSampler, SameSeedSameCommands) {
  VelocityCommandSampler a({}), b({});
  const std::uint64_t seed = 11;
  a.reset(&seed);
  b.reset(&seed);
  for (int step = 0; step < 2000; ++step) {
    a.advance(0.02);
    b.advance(0.02);
    ASSERT_EQ(a.command(), b.command());
  }
}

TEST(VelocityCommandSampler, WithoutResamplingOneCommandPerEpisode) {
  VelocityCommandRanges ranges;
  ranges.resample_time_min = 0.0;
  ranges.resample_time_max = 0.0;
  ranges.zero_command_probability = 0.0;
  VelocityCommandSampler sampler(ranges);
  const std::uint64_t seed = 1;
  sampler.reset(&seed);
  const VelocityCommand first = sampler.command();
  for (int step = 0; step < 1000; ++step) EXPECT_FALSE(sampler.advance(0.02));
  EXPECT_EQ(sampler.command(), first);
}

// A robot run starts standing still: with command_start_delay the command is zero for that
// long, then the draws are those of an undelayed sampler from the same seed.
TEST(VelocityCommandSampler, StartDelayHoldsZeroThenDrawsTheSameSequence) {
  VelocityCommandRanges delayed_ranges;
  delayed_ranges.zero_command_probability = 0.0;
  VelocityCommandRanges plain_ranges = delayed_ranges;
  delayed_ranges.start_delay = 1.0;
  VelocityCommandSampler delayed(delayed_ranges), plain(plain_ranges);
  const std::uint64_t seed = 5;
  delayed.reset(&seed);
  plain.reset(&seed);
  EXPECT_EQ(delayed.command(), VelocityCommand{});
  int steps = 0;
  while (!delayed.advance(0.02)) {
    EXPECT_EQ(delayed.command(), VelocityCommand{});
    ++steps;
  }
  EXPECT_NEAR(steps, 49, 1);  // the 50th step of 20 ms ends the 1 s hold (rounding: 51st)
  EXPECT_EQ(delayed.command(), plain.command());
  EXPECT_NE(plain.command(), VelocityCommand{});
  delayed_ranges.start_delay = -1.0;
  EXPECT_THROW(VelocityCommandSampler{delayed_ranges}, std::invalid_argument);
}

TEST(VelocityReward, TermsAtPerfectTrackingAndAtOneKernelWidth) {
  VelocityReward reward;
  const std::array<float, 6> action{0.5f, 0, 0, 0, 0, 0};
  const std::array<float, 6> previous{0.0f, 0, 0, 0, 0, 0.2f};
  VelocityRewardInputs inputs;
  inputs.command = {0.5, -1.0};
  inputs.velocity = {0.5, -1.0};
  inputs.action = action;
  inputs.previous_action = previous;
  double total = reward(inputs);
  const auto& terms = reward.terms();
  EXPECT_DOUBLE_EQ(terms[VelocityReward::kTrackForwardVelocity], 2.0);
  EXPECT_DOUBLE_EQ(terms[VelocityReward::kTrackYawRate], 2.0);
  EXPECT_DOUBLE_EQ(terms[VelocityReward::kUpright], 1.0);
  EXPECT_DOUBLE_EQ(terms[VelocityReward::kPose], 0.5);
  EXPECT_NEAR(terms[VelocityReward::kActionRate], -0.1 * (0.25 + 0.04), 1e-7);
  EXPECT_NEAR(total, 5.5 - 0.029, 1e-7);

  // One kernel width off on each velocity, tilted, legs off the default pose.
  inputs.velocity = {0.25, -0.5};
  inputs.gravity_in_base = Eigen::Vector3d(std::sqrt(0.1), 0.0, -std::sqrt(0.9));
  inputs.leg_deviation = {0.5, 0.0, 0.0, 0.0};
  total = reward(inputs);
  EXPECT_NEAR(terms[VelocityReward::kTrackForwardVelocity], 2.0 / std::numbers::e, 1e-12);
  EXPECT_NEAR(terms[VelocityReward::kTrackYawRate], 2.0 / std::numbers::e, 1e-12);
  EXPECT_NEAR(terms[VelocityReward::kUpright], 1.0 / std::numbers::e, 1e-12);
  EXPECT_NEAR(terms[VelocityReward::kPose], 0.5 / std::numbers::e, 1e-12);
  double sum = 0.0;
  for (const double term : terms) sum += term;
  EXPECT_DOUBLE_EQ(total, sum);
}

TEST(VelocityReward, LegSymmetryPenalisesScissoredLegsNotASymmetricCrouch) {
  VelocityRewardWeights weights;
  weights.w_leg_symmetry = 2.0;
  VelocityReward reward(weights);
  VelocityRewardInputs inputs;
  // A symmetric crouch: the right leg's angles are the left's negated.
  inputs.leg_deviation = {0.3, -0.6, -0.3, 0.6};
  reward(inputs);
  EXPECT_DOUBLE_EQ(reward.terms()[VelocityReward::kLegSymmetry], 0.0);
  // Scissored hips (both negative: one leg swung back, the other forward), a knee bent.
  inputs.leg_deviation = {-0.3, 0.0, -0.5, 0.2};
  reward(inputs);
  EXPECT_NEAR(reward.terms()[VelocityReward::kLegSymmetry], -2.0 * (0.64 + 0.04), 1e-12);
  // Off by default: the configurations before the term are unchanged.
  VelocityReward unweighted;
  unweighted(inputs);
  EXPECT_EQ(unweighted.terms()[VelocityReward::kLegSymmetry], 0.0);
}

TEST(VelocityReward, HeightErrorPenaltyIsTheAbsoluteErrorWithAHeightCommandOnly) {
  VelocityRewardWeights weights;
  weights.w_height_error = 30.0;
  VelocityReward reward(weights);
  VelocityRewardInputs inputs;
  inputs.track_height = true;
  inputs.command.height = 0.53;
  inputs.velocity.height = 0.55;  // 2 cm above the command
  reward(inputs);
  EXPECT_NEAR(reward.terms()[VelocityReward::kHeightError], -30.0 * 0.02, 1e-12);
  inputs.velocity.height = 0.51;  // as far below
  reward(inputs);
  EXPECT_NEAR(reward.terms()[VelocityReward::kHeightError], -30.0 * 0.02, 1e-12);
  inputs.track_height = false;
  reward(inputs);
  EXPECT_EQ(reward.terms()[VelocityReward::kHeightError], 0.0);
  // Off by default.
  VelocityReward unweighted;
  inputs.track_height = true;
  unweighted(inputs);
  EXPECT_EQ(unweighted.terms()[VelocityReward::kHeightError], 0.0);
}

TEST(VelocityReward, ForwardErrorPenaltyIsTheSquaredErrorCappedAtOneMetrePerSecond) {
  VelocityRewardWeights weights;
  weights.w_forward_velocity_error = 2.0;
  VelocityReward reward(weights);
  VelocityRewardInputs inputs;
  inputs.command.forward_velocity = 0.5;
  inputs.velocity.forward_velocity = 0.2;  // 0.3 m/s behind the command
  reward(inputs);
  EXPECT_NEAR(reward.terms()[VelocityReward::kForwardVelocityError], -2.0 * 0.09, 1e-12);
  inputs.velocity.forward_velocity = 0.8;  // as far ahead
  reward(inputs);
  EXPECT_NEAR(reward.terms()[VelocityReward::kForwardVelocityError], -2.0 * 0.09, 1e-12);
  // Capped: a robot 3 m/s off costs what one 1 m/s off costs.
  inputs.velocity.forward_velocity = -2.5;
  reward(inputs);
  EXPECT_NEAR(reward.terms()[VelocityReward::kForwardVelocityError], -2.0, 1e-12);
  // Off by default.
  VelocityReward unweighted;
  unweighted(inputs);
  EXPECT_EQ(unweighted.terms()[VelocityReward::kForwardVelocityError], 0.0);
}

TEST(VelocityReward, TiltExcessPenaltyGrowsLinearlyBeyondItsStart) {
  VelocityRewardWeights weights;
  weights.w_tilt_excess = 10.0;
  weights.tilt_excess_start = 0.3;
  VelocityReward reward(weights);
  VelocityRewardInputs inputs;
  const auto tilted = [](double tilt) {  // gravity in the frame of a base pitched by tilt
    return Eigen::Vector3d(std::sin(tilt), 0.0, -std::cos(tilt));
  };
  inputs.gravity_in_base = tilted(0.25);  // below the start: free
  reward(inputs);
  EXPECT_EQ(reward.terms()[VelocityReward::kTiltExcess], 0.0);
  inputs.gravity_in_base = tilted(0.35);
  reward(inputs);
  EXPECT_NEAR(reward.terms()[VelocityReward::kTiltExcess], -10.0 * 0.05, 1e-9);
  inputs.gravity_in_base = tilted(-0.45);  // leaning back counts alike
  reward(inputs);
  EXPECT_NEAR(reward.terms()[VelocityReward::kTiltExcess], -10.0 * 0.15, 1e-9);
  // Off by default.
  VelocityReward unweighted;
  unweighted(inputs);
  EXPECT_EQ(unweighted.terms()[VelocityReward::kTiltExcess], 0.0);
}

/// A tilt penalty of its own angle (the shins', the floor's): its weight, its start, the
/// input it reads and its term.
struct TiltPenalty {
  double VelocityRewardWeights::*weight;
  double VelocityRewardWeights::*start;
  double VelocityRewardInputs::*angle;
  VelocityReward::Term term;
};

TEST(VelocityReward, ShinAndFloorTiltPenaltiesGrowLinearlyBeyondTheirStart) {
  for (const TiltPenalty& penalty :
       {TiltPenalty{&VelocityRewardWeights::w_shin_tilt_excess,
                    &VelocityRewardWeights::shin_tilt_excess_start,
                    &VelocityRewardInputs::shin_tilt, VelocityReward::kShinTiltExcess},
        TiltPenalty{&VelocityRewardWeights::w_floor_tilt_excess,
                    &VelocityRewardWeights::floor_tilt_excess_start,
                    &VelocityRewardInputs::floor_tilt, VelocityReward::kFloorTiltExcess}}) {
    VelocityRewardWeights weights;
    weights.*penalty.weight = 10.0;
    weights.*penalty.start = 0.3;
    VelocityReward reward(weights);
    VelocityRewardInputs inputs;
    inputs.*penalty.angle = 0.25;  // below the start: free
    reward(inputs);
    EXPECT_EQ(reward.terms()[penalty.term], 0.0);
    inputs.*penalty.angle = 0.42;
    reward(inputs);
    EXPECT_NEAR(reward.terms()[penalty.term], -10.0 * 0.12, 1e-9);
    // The tilt from gravity does not enter it: that is w_tilt_excess's (0 here).
    inputs.gravity_in_base = Eigen::Vector3d(std::sin(0.6), 0.0, -std::cos(0.6));
    reward(inputs);
    EXPECT_NEAR(reward.terms()[penalty.term], -10.0 * 0.12, 1e-9);
    EXPECT_EQ(reward.terms()[VelocityReward::kTiltExcess], 0.0);
    VelocityReward unweighted;  // off by default
    unweighted(inputs);
    EXPECT_EQ(unweighted.terms()[penalty.term], 0.0);
  }
}

/// An observation of a base rotated by `rotation`, moving at `velocity` in the world.
Observation base_state(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& velocity,
                       const Eigen::Vector3d& angular_velocity_in_base) {
  Observation observation;
  observation.has_sim = true;
  observation.base_orientation.rotation_base_to_world = rotation;
  observation.base_orientation.angular_velocity = angular_velocity_in_base;
  observation.sim_base.linear_velocity = velocity;
  return observation;
}

TEST(VelocityTask, MeasuredVelocityAlongTheHeadingAndAboutTheVertical) {
  const Eigen::Matrix3d yawed =
      Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  // Facing +y, moving +y at 0.7 m/s while turning at 0.3 rad/s.
  Observation full = base_state(yawed, {0.0, 0.7, 0.0}, {0.0, 0.0, 0.3});
  BaseVelocity velocity = VelocityTask::measured_velocity(full);
  EXPECT_NEAR(velocity.forward_velocity, 0.7, 1e-12);
  EXPECT_NEAR(velocity.yaw_rate, 0.3, 1e-12);
  // A real robot: wheel odometry.
  full.has_sim = false;
  full.wheel_odometry.velocity = -0.4;
  velocity = VelocityTask::measured_velocity(full);
  EXPECT_NEAR(velocity.forward_velocity, -0.4, 1e-12);
}

TEST(VelocityTask, TerminatesOnTiltAndOnNonWheelContact) {
  VelocityTask task(*RobotModel::default_model(), {}, /*height_command=*/false);
  const Act action{};
  const auto pitched = [](double angle) {
    return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).toRotationMatrix();
  };
  Observation full = base_state(pitched(1.0), {}, {});
  EXPECT_FALSE(task.evaluate(full, {}, action, action).terminated);
  full = base_state(pitched(-1.3), {}, {});
  EXPECT_TRUE(task.evaluate(full, {}, action, action).terminated);
  EXPECT_EQ(task.termination_reason(), VelocityTermination::kTilt);
  full = base_state(pitched(0.1), {}, {});
  full.floor_contact.non_wheel = true;
  EXPECT_TRUE(task.evaluate(full, {}, action, action).terminated);
  EXPECT_EQ(task.termination_reason(), VelocityTermination::kContact);
  VelocityTaskConfig lenient;
  lenient.terminate_on_contact = false;
  VelocityTask without_contact(*RobotModel::default_model(), lenient, false);
  EXPECT_FALSE(without_contact.evaluate(full, {}, action, action).terminated);
}

// The task gives the reward the shins' tilt of the pose it measures: the base's lean minus
// the legs' forward swing.
TEST(VelocityTask, RewardsTheShinTiltOfTheMeasuredPose) {
  VelocityTaskConfig config;
  config.reward.w_shin_tilt_excess = 10.0;
  config.reward.shin_tilt_excess_start = 0.3;
  VelocityTask task(*RobotModel::default_model(), config, /*height_command=*/false);
  const Act action{};
  const Eigen::Matrix3d leaning =
      Eigen::AngleAxisd(0.45, Eigen::Vector3d::UnitY()).toRotationMatrix();
  Observation full = base_state(leaning, {}, {});
  task.evaluate(full, {}, action, action);  // straight legs: the shins lean 0.45 rad
  EXPECT_NEAR(task.reward().terms()[VelocityReward::kShinTiltExcess], -10.0 * 0.15, 1e-9);
  full.servo[kLeftHip].position = 0.2;  // both legs swung forward by 0.2 rad
  full.servo[kRightHip].position = -0.2;
  task.evaluate(full, {}, action, action);
  EXPECT_EQ(task.reward().terms()[VelocityReward::kShinTiltExcess], 0.0);
  full.servo[kRightHip].position = 0.0;  // the right shin still leans with the base
  task.evaluate(full, {}, action, action);
  EXPECT_NEAR(task.reward().terms()[VelocityReward::kShinTiltExcess], -10.0 * 0.15, 1e-9);
}

// On a slope the simulation tilts gravity, not the floor: the base upright to gravity leans
// from the floor's normal by the slope (its ground truth), and the task rewards that lean.
TEST(VelocityTask, RewardsTheTiltFromTheFloorsNormal) {
  VelocityTaskConfig config;
  config.reward.w_floor_tilt_excess = 10.0;
  config.reward.floor_tilt_excess_start = 0.3;
  VelocityTask task(*RobotModel::default_model(), config, /*height_command=*/false);
  const Act action{};
  const auto pitched = [](double angle) {
    return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).toRotationMatrix();
  };
  // Leaning 0.25 rad back from gravity, facing down a slope of 0.14 rad: 0.39 rad from the
  // floor's normal.
  Observation full = base_state(pitched(-0.25), {}, {});
  full.sim_base.orientation = Eigen::Quaterniond(pitched(-0.39));
  EXPECT_NEAR(VelocityTask::tilt(full), 0.25, 1e-12);
  EXPECT_NEAR(VelocityTask::floor_tilt(full), 0.39, 1e-12);
  task.evaluate(full, {}, action, action);
  EXPECT_NEAR(task.reward().terms()[VelocityReward::kFloorTiltExcess], -10.0 * 0.09, 1e-9);
  // A robot knows no slope: the tilt from gravity.
  full.has_sim = false;
  EXPECT_NEAR(VelocityTask::floor_tilt(full), 0.25, 1e-12);
  task.evaluate(full, {}, action, action);
  EXPECT_EQ(task.reward().terms()[VelocityReward::kFloorTiltExcess], 0.0);
}

TEST(VelocityTask, GravityAndPitchOfTheObservation) {
  VelocityTask task(*RobotModel::default_model(), {}, /*height_command=*/false);
  const Eigen::Matrix3d pitched =
      Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  Observation full = base_state(pitched, {}, {0.0, 0.5, 0.0});
  full.servo[kLeftKnee].position = 0.3;
  full.servo[kRightWheel].velocity = -4.0;
  LegacyObs observation{};
  const Act last{0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f};
  task.write_observation(full, last, {0.7, -0.2}, observation);
  const BoxSpace space = VelocityTask::make_observation_space(false);
  EXPECT_FLOAT_EQ(observation[space.index_of("left_knee.position")], 0.3f);
  EXPECT_FLOAT_EQ(observation[space.index_of("right_wheel.velocity")], -4.0f);
  // Leaning forward by θ: gravity (sin θ, 0, -cos θ) in the base frame.
  EXPECT_NEAR(observation[space.index_of("gravity.x")], std::sin(0.2), 1e-6);
  EXPECT_NEAR(observation[space.index_of("gravity.z")], -std::cos(0.2), 1e-6);
  EXPECT_FLOAT_EQ(observation[space.index_of("gyro.y")], 0.5f);
  EXPECT_FLOAT_EQ(observation[space.index_of("last_action.right_wheel")], 0.6f);
  EXPECT_FLOAT_EQ(observation[VelocityTask::kCommandIndex], 0.7f);
  EXPECT_FLOAT_EQ(observation[space.index_of("command.yaw_rate")], -0.2f);
}

// The sizes the code declares as constants (buffers, tests) and the sizes of the spaces
// and tasks built from the options agree for every combination of the optional columns.
TEST(VelocityTask, ObservationSizesAreTheSpacesSizes) {
  EXPECT_EQ(VelocityTask::make_observation_space(false).size(), VelocityTask::kObservationSize);
  EXPECT_EQ(VelocityTask::make_observation_space(true).size(),
            VelocityTask::kHeightObservationSize);
  EXPECT_EQ(VelocityTask::make_observation_space(true, true, true).size(),
            VelocityTask::kMaxObservationSize);
  for (const bool height_command : {false, true}) {
    for (const bool command_acceleration : {false, true}) {
      for (const bool imu_acceleration : {false, true}) {
        VelocityTaskConfig config;
        config.observe_command_acceleration = command_acceleration;
        config.observe_acceleration = imu_acceleration;
        const VelocityTask task(*RobotModel::default_model(), config, height_command);
        EXPECT_EQ(task.observation_size(),
                  VelocityTask::make_observation_space(height_command, command_acceleration,
                                                       imu_acceleration)
                      .size());
      }
    }
  }
}

TEST(VelocityEnv, ActionMappingAroundTheDefaultPose) {
  auto simulation = std::make_unique<testing::ScriptedSimulation>(0.02);
  testing::ScriptedSimulation* scripted = simulation.get();
  // The policies of before the height command: legs within ±0.5 rad, 20 observations.
  VelocityTaskConfig task;
  task.leg_action_scale = 0.5;
  VelocityCommandRanges commands;
  commands.height_command = false;
  VelocityEnv env(std::make_unique<ServosEnv>(std::move(simulation), RobotModel::default_model()),
                  task, commands);
  LegacyObs observation{};
  env.reset(0, observation);
  const Act action{1.0f, -0.5f, 0.5f, 0.0f, 3.0f, -1.0f};
  env.step(action, observation);
  const ServoAction& sent = scripted->received.back();
  EXPECT_NEAR(sent[kLeftHip].position, 0.5, 1e-9);
  EXPECT_NEAR(sent[kLeftKnee].position, -0.25, 1e-9);
  EXPECT_NEAR(sent[kRightKnee].position, 0.5, 1e-9);  // clamped to 1
  EXPECT_NEAR(sent[kLeftWheel].velocity, 30.0, 1e-9);
  EXPECT_NEAR(sent[kRightWheel].velocity, -60.0, 1e-9);
  EXPECT_TRUE(std::isnan(sent[kLeftWheel].position));
  // The last action, clamped, is observed.
  EXPECT_FLOAT_EQ(observation[12 + 4], 1.0f);
}

TEST(VelocityEnv, RelativeWheelActionStartsFromTheMeasuredWheelVelocities) {
  auto simulation = std::make_unique<testing::ScriptedSimulation>(0.02);
  testing::ScriptedSimulation* scripted = simulation.get();
  scripted->on_reset.servo[kLeftWheel].velocity = 10.0;
  scripted->on_reset.servo[kRightWheel].velocity = -8.0;
  Observation second = scripted->on_reset;
  second.servo[kLeftWheel].velocity = 12.0;
  scripted->script = {second};
  VelocityTaskConfig task;
  task.relative_wheel_action = true;
  task.wheel_velocity_scale = 3.0;
  VelocityEnv env(std::make_unique<ServosEnv>(std::move(simulation), RobotModel::default_model()),
                  task, VelocityCommandRanges{});
  Obs observation{};
  env.reset(0, observation);
  const Act action{0.0f, 0.0f, 0.5f, 0.0f, 0.0f, -1.0f};
  env.step(action, observation);
  EXPECT_NEAR(scripted->received.back()[kLeftWheel].velocity, 11.5, 1e-9);
  EXPECT_NEAR(scripted->received.back()[kRightWheel].velocity, -11.0, 1e-9);
  // The next step starts from the velocities the last step measured.
  env.step(action, observation);
  EXPECT_NEAR(scripted->received.back()[kLeftWheel].velocity, 13.5, 1e-9);
  // The legs keep their absolute targets.
  EXPECT_NEAR(scripted->received.back()[kLeftHip].position, 0.0, 1e-9);
}

TEST(VelocityEnv, WheelFeedforwardAddsTheFollowedCommandsWheelSpeeds) {
  auto simulation = std::make_unique<testing::ScriptedSimulation>(0.02);
  testing::ScriptedSimulation* scripted = simulation.get();
  VelocityTaskConfig task;
  task.wheel_command_feedforward = true;
  task.wheel_velocity_scale = 10.0;
  VelocityCommandRanges commands;
  commands.max_acceleration = 0.0;  // steps: the followed command is the override at once
  const auto model = RobotModel::default_model();
  VelocityEnv env(std::make_unique<ServosEnv>(std::move(simulation), model), task, commands);
  env.set_command_override(VelocityCommand{0.5, 1.0, kStandingBaseHeight});
  Obs observation{};
  env.reset(0, observation);
  const Act action{0.0f, 0.0f, 0.1f, 0.0f, 0.0f, 0.0f};
  env.step(action, observation);
  const double forward = 0.5 / model->wheel_radius();
  const double turn = -0.5 * model->track() / model->wheel_radius() * 1.0;
  // 1e-6: the action 0.1f is a float.
  EXPECT_NEAR(scripted->received.back()[kLeftWheel].velocity, forward + turn + 1.0, 1e-6);
  EXPECT_NEAR(scripted->received.back()[kRightWheel].velocity, -forward + turn, 1e-9);
  task.relative_wheel_action = true;
  const std::string message =
      error_message([&] { VelocityTask both(*model, task, /*height_command=*/true); });
  EXPECT_NE(message.find("relative_wheel_action"), std::string::npos) << message;
}

TEST(VelocityEnv, RelativeWheelActionRefusesTheBalancer) {
  const std::string message = error_message([] {
    make_env("Upkie-Mock-Velocity", {{"relative_wheel_action", "true"},
                                     {"base_controller", "balancer:1,2,3,4,5,6,7,8,9,10"}});
  });
  EXPECT_NE(message.find("relative_wheel_action"), std::string::npos) << message;
  EXPECT_NE(message.find("base_controller"), std::string::npos) << message;
}

TEST(VelocityEnv, OverrideReplacesTheRandomCommandsFromTheNextObservation) {
  // Steps, so that the command is the target at once (velocity_command_limiter_test ramps).
  auto env = make_env("Upkie-Mock-Velocity", {{"command_max_acceleration", "0"}});
  VelocityEnv* velocity = find_velocity_env(*env);
  ASSERT_NE(velocity, nullptr);
  Obs observation{};
  env->reset(5, observation);
  const VelocityCommand random = velocity->command();
  EXPECT_FLOAT_EQ(observation[VelocityTask::kCommandIndex], random.forward_velocity);
  velocity->set_command_override(VelocityCommand{0.4, -0.9});
  const Act action{};
  env->step(action, observation);
  EXPECT_EQ(velocity->last_step_command(), random);  // the step shown, rewarded
  EXPECT_FLOAT_EQ(observation[VelocityTask::kCommandIndex], 0.4f);
  EXPECT_FLOAT_EQ(observation[VelocityTask::kCommandIndex + 1], -0.9f);
  EXPECT_THROW(velocity->set_command_override(VelocityCommand{NAN, 0.0}), std::invalid_argument);
  velocity->set_command_override(std::nullopt);
  env->step(action, observation);
  EXPECT_EQ(velocity->command(), velocity->command_override().value_or(velocity->command()));
}

TEST(VelocityEnv, RewardIsTheSumOfItsLoggedTerms) {
  auto env = make_env("Upkie-MuJoCo-Velocity");
  ASSERT_EQ(env->reward_term_names().size(), static_cast<std::size_t>(VelocityReward::kNumTerms));
  EXPECT_EQ(env->reward_term_names()[0], "track_forward_velocity");
  Obs observation{};
  env->reset(0, observation);
  const Act action{0.1f, 0.0f, 0.05f, 0.0f, -0.1f, -0.05f};
  for (int step = 0; step < 20; ++step) {
    const StepResult result = env->step(action, observation);
    double sum = 0.0;
    for (const double term : env->reward_terms()) sum += term;
    EXPECT_NEAR(result.reward, sum, 1e-12);
  }
}

/// Steps `id` with legs straight and wheels free until the episode ends (the robot falls
/// over); the reason it ended.
VelocityTermination fall_over(const std::string& id) {
  // No tilt limit: only the contact of a leg or the base with the floor ends it.
  auto env = make_env(id, {{"fall_tilt", "3.2"}, {"init_rand_pitch", "0.3"}});
  Obs observation{};
  env->reset(1, observation);
  const Act action{};
  for (int step = 0; step < 250; ++step) {
    if (env->step(action, observation).terminated) break;
  }
  return find_velocity_env(*env)->termination_reason();
}

TEST(VelocityEnv, NonWheelContactDetectedOnMujoco) {
  EXPECT_EQ(fall_over("Upkie-MuJoCo-Velocity"), VelocityTermination::kContact);
}

TEST(VelocityEnv, NonWheelContactDetectedOnBullet) {
  EXPECT_EQ(fall_over("Upkie-Bullet-Velocity"), VelocityTermination::kContact);
}

TEST(VelocityEnv, StandingUprightTouchesTheFloorWithTheWheelsOnly) {
  for (const char* id : {"Upkie-MuJoCo-Velocity", "Upkie-Bullet-Velocity"}) {
    auto env = make_env(id);
    Obs observation{};
    env->reset(0, observation);
    const Act action{};
    for (int step = 0; step < 10; ++step) env->step(action, observation);  // settle: 0.2 s
    const Observation* full = env->full_observation();
    EXPECT_TRUE(full->floor_contact.contact) << id;
    EXPECT_FALSE(full->floor_contact.non_wheel) << id;
  }
}

TEST(VelocityEnv, RegisteredWithTheTaskRateAndTimeLimit) {
  for (const char* id :
       {"Upkie-MuJoCo-Velocity", "Upkie-Bullet-Velocity", "Upkie-Spine-Velocity"}) {
    const auto ids = registered_env_ids();
    EXPECT_NE(std::find(ids.begin(), ids.end(), id), ids.end()) << id;
  }
  auto env = make_env("Upkie-Bullet-Velocity");
  EXPECT_DOUBLE_EQ(env->timestep(), 0.02);
  EXPECT_EQ(env->physics_steps_per_step(), 20);  // 1 ms, the reference
  EXPECT_EQ(make_env("Upkie-MuJoCo-Velocity")->physics_steps_per_step(), 20);
}

TEST(VelocityEnv, CommandCurriculumNarrowsTheDrawsUntilTheScaleReachesOne) {
  // Commands held 0.02 s: a new draw every step.
  auto env = make_env("Upkie-Mock-Velocity", {{"command_curriculum_start", "0.2"},
                                              {"command_max_acceleration", "0"},
                                              {"command_resample_time_min", "0.02"},
                                              {"command_resample_time_max", "0.02"},
                                              {"zero_command_probability", "0"}});
  VelocityEnv* velocity = find_velocity_env(*env);
  ASSERT_NE(velocity, nullptr);
  const VelocityCommandRanges& ranges = velocity->command_ranges();
  EXPECT_DOUBLE_EQ(ranges.curriculum_scale(0.0), 0.2);
  EXPECT_DOUBLE_EQ(ranges.curriculum_scale(0.5), 0.6);
  const auto largest_forward_velocity = [&](double scale) {
    env->set_randomization_scale(scale);
    Obs observation{};
    env->reset(9, observation);
    double largest = 0.0;
    for (int step = 0; step < 200; ++step) {
      env->step(Act{}, observation);
      largest = std::max(largest, std::abs(velocity->target().forward_velocity));
    }
    return largest;
  };
  const double at_start = largest_forward_velocity(0.0);
  EXPECT_LE(at_start, 0.2 * ranges.max_forward_velocity);
  EXPECT_GT(at_start, 0.15 * ranges.max_forward_velocity);
  EXPECT_GT(largest_forward_velocity(1.0), 0.9 * ranges.max_forward_velocity);
  for (const char* value : {"-0.1", "1.5", "nan"}) {
    EXPECT_NE(error_message([&] {
                make_env("Upkie-Mock-Velocity", {{"command_curriculum_start", value}});
              }).find("command_curriculum_start"),
              std::string::npos)
        << value;
  }
}

TEST(VelocityEnv, BadOptionsNameTheOption) {
  const std::string id = "Upkie-Mock-Velocity";
  for (const char* option : {"max_forward_velocity", "max_yaw_rate", "zero_command_probability",
                             "command_resample_time_min", "command_max_acceleration",
                             "command_max_yaw_acceleration", "fall_tilt"}) {
    EXPECT_NE(error_message([&] {
                make_env(id, {{option, "-1"}});
              }).find(option),
              std::string::npos)
        << option;
    EXPECT_NE(error_message([&] {
                make_env(id, {{option, "nan"}});
              }).find(option),
              std::string::npos)
        << option;
  }
  const std::string crossed = error_message([&] {
    make_env(id, {{"command_resample_time_min", "6"}, {"command_resample_time_max", "3"}});
  });
  EXPECT_NE(crossed.find("command_resample_time_min"), std::string::npos) << crossed;
  EXPECT_NE(crossed.find("command_resample_time_max"), std::string::npos) << crossed;
  EXPECT_NE(error_message([&] {
              make_env(id, {{"zero_command_probability", "1.5"}});
            }).find("zero_command_probability"),
            std::string::npos);
  for (const char* value : {"-1", "nan", "2"}) {
    EXPECT_NE(error_message([&] {
                make_env(id, {{"residual_scale", value}});
              }).find("residual_scale"),
              std::string::npos)
        << value;
  }
  for (const char* spec : {"balancer:1,2", "zero2", "linear:1,2,3,nan"}) {
    EXPECT_NE(error_message([&] {
                make_env(id, {{"base_controller", spec}});
              }).find("base_controller"),
              std::string::npos)
        << spec;
  }
}

}  // namespace
}  // namespace upkie_rl
