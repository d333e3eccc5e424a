/// The body-height command of the velocity task: the legs' kinematics, the random heights,
/// the options and the command files that carry them, the observation, the reward's term,
/// and the classical baseline crouching on both engines.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/temp_files.hpp"
#include "common/velocity_baseline.hpp"
#include "envs/controllers/builtin_controllers.hpp"
#include "envs/kinds/velocity_env.hpp"
#include "envs/registry/env_factory.hpp"
#include "envs/tasks/leg_kinematics.hpp"
#include "envs/tasks/velocity_command_schedule.hpp"
#include "envs/tasks/velocity_tracking.hpp"

namespace upkie_rl {
namespace {

/// A file of `bytes` in the test's temporary folder; its path.
std::filesystem::path command_file(const std::string& name, const std::string& bytes) {
  const std::filesystem::path path = upkie_rl::testing::temp_path("height_" + name);
  upkie_rl::testing::write_bytes(path, bytes);
  return path;
}

/// configs/velocity.yaml's base controller: `--controller lqr` designed on MuJoCo.
constexpr const char* kMujocoBaseline = testing::kVelocityBaseline;

using Obs = std::array<float, VelocityTask::kHeightObservationSize>;
using Act = std::array<float, VelocityTask::kActionSize>;

TEST(LegKinematics, StandingHeightOfTheDescription) {
  const LegKinematics legs(*RobotModel::default_model());
  EXPECT_NEAR(legs.hip_depth(), 0.164, 1e-9);
  EXPECT_NEAR(legs.thigh_length(), 0.168, 1e-9);
  EXPECT_NEAR(legs.shin_length(), 0.175, 1e-9);
  EXPECT_NEAR(legs.standing_height(), kStandingBaseHeight, 1e-9);
  const CrouchPose straight = legs.crouch_pose(kStandingBaseHeight);
  EXPECT_EQ(straight.hip, 0.0);
  EXPECT_EQ(straight.knee, 0.0);
}

TEST(LegKinematics, CrouchPoseGivesItsHeightWithTheWheelUnderTheHip) {
  const LegKinematics legs(*RobotModel::default_model());
  const Eigen::Matrix3d upright = Eigen::Matrix3d::Identity();
  for (const double height : {0.36, 0.40, 0.45, 0.50, 0.55}) {
    const CrouchPose pose = legs.crouch_pose(height);
    EXPECT_LT(pose.knee, 0.0) << height;
    EXPECT_GT(pose.hip, 0.0) << height;
    const std::array<double, 4> angles = {pose.hip, pose.knee, -pose.hip, -pose.knee};
    EXPECT_NEAR(legs.base_height(angles, upright), height, 1e-9) << height;
    // Wheel under the hip: thigh and shin horizontal offsets cancel.
    const double wheel_x = legs.thigh_length() * std::sin(pose.hip) +
                           legs.shin_length() * std::sin(pose.hip + pose.knee);
    EXPECT_NEAR(wheel_x, 0.0, 1e-9) << height;
  }
  // The default range's deepest crouch: hips 0.41 rad, knees -0.80 rad, the shins tilted by
  // kMaxShinTilt (the ankles' boxes clear the floor).
  const CrouchPose deep = legs.crouch_pose(VelocityCommandRanges{}.min_height);
  EXPECT_NEAR(deep.knee, -0.80, 0.01);
  EXPECT_NEAR(deep.hip, 0.41, 0.01);
  EXPECT_NEAR(legs.height_at_shin_tilt(kMaxShinTilt), VelocityCommandRanges{}.min_height, 0.002);
  EXPECT_NEAR(legs.height_at_shin_tilt(-(deep.hip + deep.knee)), VelocityCommandRanges{}.min_height,
              1e-9);
  // The option's floor: knees 0.2 rad inside their limit.
  const RobotModel& model = *RobotModel::default_model();
  const CrouchPose lowest = legs.crouch_pose(kLowestHeightCommand);
  EXPECT_LT(-lowest.knee, model.servo_limits(kLeftKnee).upper - 0.19);
  EXPECT_LT(lowest.hip, model.servo_limits(kLeftHip).upper);
}

TEST(LegKinematics, TiltDoesNotChangeTheHeightOfAStraightLeg) {
  const LegKinematics legs(*RobotModel::default_model());
  const Eigen::Matrix3d pitched =
      Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  // Leaning by 0.2 rad on straight legs: the axle is 0.507 m from the base along the leg.
  EXPECT_NEAR(legs.base_height({0, 0, 0, 0}, pitched), 0.05 + 0.507 * std::cos(0.2), 1e-9);
}

// largest_shin_tilt against the shin's direction rotated into the world: the left shin's
// direction in the base frame is (sin(hip + knee), 0, -cos(hip + knee)) (wheel_from_hip).
TEST(LegKinematics, ShinTiltIsTheShinsAngleFromTheWorldsVertical) {
  const auto world_shin_angle = [](double pitch, double hip, double knee) {
    const Eigen::Vector3d in_base(std::sin(hip + knee), 0.0, -std::cos(hip + knee));
    const Eigen::Vector3d in_world = Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) * in_base;
    return std::abs(std::atan2(in_world.x(), -in_world.z()));
  };
  for (const double pitch : {-0.3, 0.0, 0.2, 0.4}) {
    for (const auto& [hip, knee] : std::array<std::pair<double, double>, 4>{
             {{0.0, 0.0}, {0.3, -0.1}, {0.41, -0.80}, {-0.2, 0.1}}}) {
      const double expected = world_shin_angle(pitch, hip, knee);
      // Symmetric legs (the right leg mirrors the left).
      EXPECT_NEAR(largest_shin_tilt(pitch, {hip, knee, -hip, -knee}), expected, 1e-12)
          << pitch << " " << hip << " " << knee;
      // One leg so posed, the other under the base's vertical: the larger of the two.
      EXPECT_NEAR(largest_shin_tilt(pitch, {hip, knee, 0.0, 0.0}),
                  std::max(expected, std::abs(pitch)), 1e-12);
      EXPECT_NEAR(largest_shin_tilt(pitch, {0.0, 0.0, -hip, -knee}),
                  std::max(expected, std::abs(pitch)), 1e-12);
    }
  }
  // Straight legs tilt with the base; legs swung forward by the lean keep the shins upright.
  EXPECT_NEAR(largest_shin_tilt(0.35, {0.0, 0.0, 0.0, 0.0}), 0.35, 1e-12);
  EXPECT_NEAR(largest_shin_tilt(0.35, {0.25, 0.10, -0.25, -0.10}), 0.0, 1e-12);
  // The deepest crouch's shins, at the tilt height_at_shin_tilt was asked for.
  const LegKinematics legs(*RobotModel::default_model());
  const CrouchPose crouch = legs.crouch_pose(legs.height_at_shin_tilt(0.3));
  EXPECT_NEAR(largest_shin_tilt(0.0, crouch.leg_angles()), 0.3, 1e-9);
  EXPECT_NEAR(largest_shin_tilt(0.1, crouch.leg_angles()), 0.4, 1e-9);  // leaning forward
}

TEST(HeightCommandSampler, DrawsOverTheRangeWithAShareStanding) {
  VelocityCommandRanges ranges;
  VelocityCommandSampler sampler(ranges);
  const std::uint64_t seed = 3;
  sampler.reset(&seed);
  int standing = 0;
  const int draws = 4000;
  double lowest = 1.0;
  for (int i = 0; i < draws; ++i) {
    const double height = sampler.command().height;
    ASSERT_GE(height, ranges.min_height);
    ASSERT_LE(height, ranges.max_height);
    lowest = std::min(lowest, height);
    if (height == ranges.max_height) ++standing;
    while (!sampler.advance(0.5)) {
    }
  }
  EXPECT_NEAR(static_cast<double>(standing) / draws, ranges.standing_height_probability, 0.03);
  EXPECT_LT(lowest, ranges.min_height + 0.005);
}

TEST(HeightCommandSampler, VelocityCommandsOfASeedDoNotDependOnTheHeight) {
  VelocityCommandRanges with_height;
  VelocityCommandRanges without_height;
  without_height.height_command = false;
  VelocityCommandSampler a(with_height);
  VelocityCommandSampler b(without_height);
  const std::uint64_t seed = 11;
  a.reset(&seed);
  b.reset(&seed);
  for (int i = 0; i < 50; ++i) {
    EXPECT_EQ(a.command().forward_velocity, b.command().forward_velocity);
    EXPECT_EQ(a.command().yaw_rate, b.command().yaw_rate);
    EXPECT_EQ(b.command().height, kStandingBaseHeight);
    EXPECT_EQ(a.advance(0.1), b.advance(0.1));
  }
}

TEST(HeightCommandOptions, BadValuesNameTheOption) {
  for (const auto& [option, value] :
       std::vector<std::pair<std::string, std::string>>{{"min_height_command", "nan"},
                                                        {"min_height_command", "0.2"},
                                                        {"max_height_command", "0.7"},
                                                        {"max_height_command", "inf"},
                                                        {"standing_height_probability", "1.5"},
                                                        {"command_max_height_velocity", "-1"},
                                                        {"w_track_height", "nan"},
                                                        {"height_sigma", "0"},
                                                        {"height_command", "maybe"}}) {
    try {
      make_env("Upkie-Mock-Velocity", {{option, value}});
      ADD_FAILURE() << option << "=" << value << " was accepted";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find(option), std::string::npos) << error.what();
    }
  }
  try {
    make_env("Upkie-Mock-Velocity", {{"min_height_command", "0.40"}});
    ADD_FAILURE() << "a crouch beyond leg_action_scale was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("leg_action_scale"), std::string::npos);
  }
  EXPECT_NO_THROW(make_env("Upkie-Mock-Velocity",
                           {{"min_height_command", "0.40"}, {"leg_action_scale", "2.5"}}));
  try {
    make_env("Upkie-Mock-Velocity",
             {{"min_height_command", "0.5"}, {"max_height_command", "0.45"}});
    ADD_FAILURE() << "an empty height range was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("min_height_command"), std::string::npos);
  }
}

TEST(HeightCommandSchedule, OptionalHeightColumnIsCheckedAndNamed) {
  VelocityCommandRanges ranges;
  const std::filesystem::path file =
      command_file("commands.csv", "time,vx,wz,height\n0,0,0,0.557\n1,0.2,0,0.54\n2,0,0.5,0.53\n");
  const VelocityCommandSchedule schedule = VelocityCommandSchedule::load(file, ranges);
  EXPECT_EQ(schedule.at(0.5).height, 0.557);
  EXPECT_EQ(schedule.at(1.5).height, 0.54);
  EXPECT_EQ(schedule.at(3.0).height, 0.53);
  // Without the column: standing.
  const std::filesystem::path three = command_file("three.csv", "0,0.1,0\n");
  EXPECT_EQ(VelocityCommandSchedule::load(three, ranges).at(0.0).height, kStandingBaseHeight);
  for (const char* row : {"0,0,0,0.5\n", "0,0,0,0.6\n", "0,0,0,nan\n"}) {
    const std::filesystem::path bad = command_file("bad.csv", row);
    try {
      VelocityCommandSchedule::load(bad, ranges);
      ADD_FAILURE() << row << " was accepted";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("column height"), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("height_bad.csv:1"), std::string::npos)
          << error.what();
    }
  }
  VelocityCommandRanges no_height;
  no_height.height_command = false;
  const std::filesystem::path four = command_file("four.csv", "0,0,0,0.54\n");
  EXPECT_THROW(VelocityCommandSchedule::load(four, no_height), std::invalid_argument);
}

TEST(HeightCommandEnv, ObservationEndsWithTheHeightUnlessSwitchedOff) {
  auto env = make_env("Upkie-Mock-Velocity");
  EXPECT_EQ(env->observation_space().size(), VelocityTask::kHeightObservationSize);
  EXPECT_EQ(env->observation_space().names.back(), kHeightCommandColumn);
  auto legacy = make_env("Upkie-Mock-Velocity", {{"height_command", "false"}});
  EXPECT_EQ(legacy->observation_space().size(), VelocityTask::kObservationSize);
  // A reset shows the followed height: standing, ramping toward the target.
  VelocityEnv& velocity = *find_velocity_env(*env);
  velocity.set_command_override(VelocityCommand{0.0, 0.0, 0.54});
  Obs observation{};
  env->reset(0, observation);
  EXPECT_FLOAT_EQ(observation[VelocityTask::kHeightCommandIndex], kStandingBaseHeight);
  Act action{};
  env->step(action, observation);
  EXPECT_NEAR(observation[VelocityTask::kHeightCommandIndex], kStandingBaseHeight - 0.1 * 0.02,
              1e-6);
  EXPECT_THROW(velocity.set_command_override(VelocityCommand{0.0, 0.0, 0.5}),
               std::invalid_argument);
  EXPECT_THROW(velocity.set_command_override(VelocityCommand{0.0, 0.0, std::nan("")}),
               std::invalid_argument);
}

TEST(HeightCommandEnv, TrackingTermLoggedOnlyWithAHeightCommand) {
  for (const bool height : {true, false}) {
    auto env = make_env("Upkie-MuJoCo-Velocity", {{"height_command", height ? "true" : "false"}});
    Obs observation{};
    env->reset(0, std::span<float>(observation).first(env->observation_space().size()));
    Act action{};
    env->step(action, std::span<float>(observation).first(env->observation_space().size()));
    const double term = env->reward_terms()[VelocityReward::kTrackHeight];
    if (height) {
      EXPECT_GT(term, 0.9) << "standing as commanded";
    } else {
      EXPECT_EQ(term, 0.0);
    }
    EXPECT_EQ(env->reward_term_names()[VelocityReward::kTrackHeight], "track_height");
  }
}

TEST(HeightCommandEnv, LegActionsAboutTheCrouchStartFromTheCommandedCrouch) {
  const auto model = RobotModel::default_model();
  VelocityTaskConfig about;
  about.leg_action_about_crouch = true;
  about.leg_action_scale = 0.5;
  const VelocityTask task(*model, about, /*height_command=*/true);
  const VelocityCommand crouched{0.3, 0.0, 0.535};
  const std::array<double, 4> pose = task.legs().crouch_pose(0.535).leg_angles();
  ASSERT_LT(pose[1], -0.5) << "a real crouch: the knee bends";
  const Observation measured{};
  ServoAction commands{};
  Act action{};
  action[kLeftKnee] = 0.2f;
  task.servo_action(action, measured, crouched, commands);
  for (std::size_t k = 0; k < VelocityTask::kLegJoints.size(); ++k) {
    const std::size_t joint = VelocityTask::kLegJoints[k];
    const double offset = joint == kLeftKnee ? 0.5 * 0.2 : 0.0;
    EXPECT_NEAR(commands[joint].position, pose[k] + offset, 1e-6) << kServoNames[joint];
  }
  // Without a height command, or without the option, the origin is straight legs.
  const VelocityTask no_height(*model, about, /*height_command=*/false);
  no_height.servo_action(action, measured, crouched, commands);
  EXPECT_NEAR(commands[kLeftKnee].position, 0.1, 1e-6);
  EXPECT_NEAR(commands[kRightHip].position, 0.0, 1e-12);
  VelocityTaskConfig straight = about;
  straight.leg_action_about_crouch = false;
  VelocityTask(*model, straight, true).servo_action(action, measured, crouched, commands);
  EXPECT_NEAR(commands[kLeftKnee].position, 0.1, 1e-6);
  // The deepest crouch needs no action about it: a small scale is then accepted.
  EXPECT_THROW(make_env("Upkie-Mock-Velocity", {{"leg_action_scale", "0.5"}}),
               std::invalid_argument);
  EXPECT_NO_THROW(make_env("Upkie-Mock-Velocity",
                           {{"leg_action_scale", "0.5"}, {"leg_action_about_crouch", "true"}}));
  EXPECT_THROW(make_env("Upkie-Mock-Velocity", {{"leg_action_about_crouch", "maybe"}}),
               std::invalid_argument);
}

/// Runs the classical baseline on `id` holding a crouch to `height` for 5 s; returns the
/// ground-truth base height of the last 2 s (mean) and the tracking.
struct CrouchResult {
  double mean_base_z = 0.0;
  double min_base_z = 1.0;
  VelocityTracking tracking;
  bool fell = false;
};

CrouchResult crouch_with_baseline(const std::string& id, double height,
                                  const EnvOptions& options = {}) {
  auto env = make_env(id, options);
  VelocityEnv& velocity = *find_velocity_env(*env);
  auto baseline = make_builtin_controller(kMujocoBaseline, *env);
  velocity.set_command_override(VelocityCommand{0.0, 0.0, height});
  Obs observation{};
  Act action{};
  env->reset(0, observation);
  baseline->reset();
  CrouchResult result;
  const int steps = static_cast<int>(std::lround(5.0 / env->timestep()));
  int averaged = 0;
  for (int step = 0; step < steps; ++step) {
    baseline->act(observation, action);
    const StepResult outcome = env->step(action, observation);
    result.tracking.add(velocity, outcome.terminated);
    if (outcome.terminated) {
      result.fell = true;
      break;
    }
    if (step >= steps * 3 / 5) {
      const double z = env->full_observation()->sim_base.position.z();
      result.mean_base_z += z;
      result.min_base_z = std::min(result.min_base_z, z);
      ++averaged;
    }
  }
  if (averaged > 0) result.mean_base_z /= averaged;
  return result;
}

void expect_crouch(const std::string& id) {
  const CrouchResult standing = crouch_with_baseline(id, kStandingBaseHeight);
  const double asked = VelocityCommandRanges{}.min_height;  // the default range's deepest
  const CrouchResult crouched = crouch_with_baseline(id, asked);
  ASSERT_FALSE(standing.fell);
  ASSERT_FALSE(crouched.fell);
  // The ground truth: the base went down by about the commanded 0.027 m. The baseline
  // keeps a margin for its ankles (VelocityBalancer::kCrouchShinTilt): it stops about 5 mm
  // above the range's bottom; tires sink a millimetre or so.
  EXPECT_GT(standing.mean_base_z - crouched.mean_base_z, 0.018)
      << id << ": standing " << standing.mean_base_z << " m, crouched " << crouched.mean_base_z;
  EXPECT_GT(crouched.mean_base_z, asked - 0.003) << id;
  EXPECT_LT(crouched.mean_base_z, asked + 0.008) << id;
  EXPECT_LT(crouched.tracking.rms_height(), 0.01) << id;
  std::printf(
      "%s: baseline standing at %.4f m, crouched (%.3f m asked) at %.4f m, "
      "tracking_rms_height %.4f m\n",
      id.c_str(), standing.mean_base_z, asked, crouched.mean_base_z,
      crouched.tracking.rms_height());
}

TEST(HeightCommandBaseline, CommandedCrouchLowersTheBaseOnMujoco) {
  expect_crouch("Upkie-MuJoCo-Velocity");
}

TEST(HeightCommandBaseline, CommandedCrouchLowersTheBaseOnBullet) {
  expect_crouch("Upkie-Bullet-Velocity");
}

TEST(HeightCommandBaseline, SameCrouchWithLegActionsAboutTheCrouch) {
  // The baseline takes the task's action origin off: the same servo targets, the same run.
  const double asked = VelocityCommandRanges{}.min_height;
  const CrouchResult straight = crouch_with_baseline("Upkie-MuJoCo-Velocity", asked);
  const CrouchResult about =
      crouch_with_baseline("Upkie-MuJoCo-Velocity", asked, {{"leg_action_about_crouch", "true"}});
  ASSERT_FALSE(about.fell);
  EXPECT_NEAR(about.mean_base_z, straight.mean_base_z, 1e-5);
  EXPECT_NEAR(about.tracking.rms_height(), straight.tracking.rms_height(), 1e-5);
}

}  // namespace
}  // namespace upkie_rl
