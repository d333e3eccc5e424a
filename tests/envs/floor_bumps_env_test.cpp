/// The bump options of the simulated environments (bump_height, bump_spacing, bump_width,
/// bump_ramp), on Bullet and on MuJoCo: the velocity task's classical baseline driving over
/// 1.5 cm bumps lifts its tires by 1.5 cm, meets square 2 cm ones with its ankles first,
/// and crosses 2 cm ones bevelled at 1:2.5 on its tires; bump_height 0 is the default
/// environment, bit for bit; bad values are refused by name.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "common/velocity_baseline.hpp"
#include "envs/controllers/builtin_controllers.hpp"
#include "envs/kinds/velocity_env.hpp"
#include "envs/registry/env_factory.hpp"
#include "envs/tasks/velocity_task.hpp"
#include "sim/tire_centres.hpp"

namespace upkie_rl {
namespace {

/// configs/velocity.yaml's base controller (`--controller lqr` designed on MuJoCo); it
/// drives Bullet's robot too.
constexpr const char* kBaseline = testing::kVelocityBaseline;

/// What the tires did on a drive.
struct Drive {
  double flat = 0.0;               ///< Mean height of the lower tire's centre over [0.5, 1) s [m].
  double highest = 0.0;            ///< Its highest from 0.5 s on [m].
  double final_x = 0.0;            ///< Of the base [m].
  bool non_wheel_contact = false;  ///< Whether a part other than a tire touched the floor.
  VelocityTermination termination = VelocityTermination::kNone;

  double rise() const { return highest - flat; }
};

/// The baseline driving `id` with `options` (bumps every metre by default) at `velocity`
/// [m/s] for 4.5 s from the deterministic start, or until the episode terminates.
Drive drive(const std::string& id, const EnvOptions& options, double velocity) {
  std::unique_ptr<Env> env = make_env(id, options);
  VelocityEnv* task = find_velocity_env(*env);
  std::unique_ptr<Controller> controller = make_builtin_controller(kBaseline, *env);
  task->set_command_override(VelocityCommand{velocity, 0.0});
  std::array<float, VelocityTask::kHeightObservationSize> observation{};
  std::array<float, VelocityTask::kActionSize> action{};
  env->reset(0, observation);
  controller->reset();
  const testing::TireCentres tire_centres(*RobotModel::default_model());
  Drive result;
  int flat_samples = 0;
  bool terminated = false;
  while (!terminated && env->full_observation()->time < 4.5) {
    controller->act(observation, action);
    terminated = env->step(action, observation).terminated;
    const Observation& full = *env->full_observation();
    result.non_wheel_contact = result.non_wheel_contact || full.floor_contact.non_wheel;
    const double tire =
        std::min(tire_centres(full, kLeftWheel).z(), tire_centres(full, kRightWheel).z());
    if (full.time < 0.5) continue;  // landing
    if (full.time < 1.0) {
      result.flat += tire;
      ++flat_samples;
    }
    result.highest = std::max(result.highest, tire);
  }
  result.flat /= flat_samples;
  result.final_x = env->full_observation()->sim_base.position.x();
  result.termination = task->termination_reason();
  return result;
}

class FloorBumpsEnv : public ::testing::TestWithParam<const char*> {};

TEST_P(FloorBumpsEnv, DrivingOverBumpsLiftsTheTiresByTheirHeight) {
  // Ahead and behind: the bumps at x = 1 m and x = -1 m. Measured: rises of 15.3 mm both
  // ways on Bullet, 15.1 and 15.3 mm on MuJoCo; 0.2 mm at most on the flat floor.
  for (const double velocity : {0.4, -0.4}) {
    const Drive bumps = drive(GetParam(), {{"bump_height", "0.015"}}, velocity);
    EXPECT_EQ(bumps.termination, VelocityTermination::kNone) << velocity;
    EXPECT_GT(bumps.final_x * velocity, 1.2 * 0.4) << velocity;  // past the first bump
    EXPECT_NEAR(bumps.rise(), 0.015, 2e-3) << velocity;
    const Drive flat = drive(GetParam(), {}, velocity);
    EXPECT_GT(flat.final_x * velocity, 1.2 * 0.4) << velocity;
    EXPECT_LT(flat.rise(), 1e-3) << velocity;
  }
}

TEST_P(FloorBumpsEnv, TwoCentimetreBumpsMeetTheAnklesBeforeTheTires) {
  // The description's ankle box (left_ankle_base) hangs 17.6 mm above the floor and reaches
  // 46 mm ahead of and behind the axle, further than the tire does at a 2 cm height
  // (40 mm): it touches a 2 cm bump before the tire climbs, and the velocity task ends the
  // episode on that contact (terminate_on_contact) with the tires still on the floor.
  const Drive drive_ahead = drive(GetParam(), {{"bump_height", "0.02"}}, 0.4);
  EXPECT_EQ(drive_ahead.termination, VelocityTermination::kContact);
  EXPECT_NEAR(drive_ahead.final_x, 0.95, 0.05);
  EXPECT_LT(drive_ahead.rise(), 1e-3);
}

TEST_P(FloorBumpsEnv, BevelledTwoCentimetreBumpsAreCrossedOnTheTires) {
  // With square edges (bump_ramp 0, the default) the ankle box touches the bump. On a slope
  // of 1 in bump_ramp, the box's lower front edge clears the slope by r sqrt(1 + 1/ramp²)
  // - 32 mm - 46 mm / ramp with straight legs (docs/robustness.md): 0.9 mm at 1:2, within
  // the 1 mm a contact counts from, and driving forward the robot leans into the slope; 3.4
  // mm at 1:2.5. Measured at 1:2: the box touches driving forward (not backward) on both
  // engines; at 1:2.25 and gentler, the tires cross both ways.
  const Drive square = drive(GetParam(), {{"bump_height", "0.02"}, {"bump_ramp", "0"}}, 0.4);
  EXPECT_TRUE(square.non_wheel_contact);
  EXPECT_EQ(square.termination, VelocityTermination::kContact);
  const Drive steep = drive(GetParam(), {{"bump_height", "0.02"}, {"bump_ramp", "2"}}, 0.4);
  EXPECT_TRUE(steep.non_wheel_contact);
  for (const double velocity : {0.4, -0.4}) {
    const Drive bevelled =
        drive(GetParam(), {{"bump_height", "0.02"}, {"bump_ramp", "2.5"}}, velocity);
    EXPECT_FALSE(bevelled.non_wheel_contact) << velocity;
    EXPECT_EQ(bevelled.termination, VelocityTermination::kNone) << velocity;
    EXPECT_GT(bevelled.final_x * velocity, 1.2 * 0.4) << velocity;  // past the first bump
    EXPECT_NEAR(bevelled.rise(), 0.02, 2e-3) << velocity;
  }
}

/// The base positions of a 200-step episode (4 s) of the baseline under random commands.
std::vector<Eigen::Vector3d> episode(const std::string& id, const EnvOptions& options) {
  std::unique_ptr<Env> env = make_env(id, options);
  std::unique_ptr<Controller> controller = make_builtin_controller(kBaseline, *env);
  std::array<float, VelocityTask::kHeightObservationSize> observation{};
  std::array<float, VelocityTask::kActionSize> action{};
  env->reset(7, observation);
  controller->reset();
  std::vector<Eigen::Vector3d> positions;
  for (int step = 0; step < 200; ++step) {
    controller->act(observation, action);
    env->step(action, observation);
    positions.push_back(env->full_observation()->sim_base.position);
  }
  return positions;
}

TEST_P(FloorBumpsEnv, HeightZeroIsTheDefaultEnvironmentBitForBit) {
  const EnvOptions commands = {{"init_rand_pitch", "0.1"}, {"max_forward_velocity", "0.8"}};
  EnvOptions zero_height = commands;
  zero_height.insert(zero_height.end(),
                     {{"bump_height", "0"}, {"bump_spacing", "0.2"}, {"bump_width", "0.1"}});
  const std::vector<Eigen::Vector3d> expected = episode(GetParam(), commands);
  const std::vector<Eigen::Vector3d> actual = episode(GetParam(), zero_height);
  for (std::size_t step = 0; step < expected.size(); ++step) {
    ASSERT_EQ(actual[step], expected[step]) << "step " << step;
  }
  EXPECT_GT((expected.back() - expected.front()).norm(), 0.05);  // it drove
}

/// The message of the std::invalid_argument that `options` make `id`'s factory throw, or
/// "" if they do not.
std::string refusal(const std::string& id, const EnvOptions& options) {
  try {
    make_env_factory(id, options);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST_P(FloorBumpsEnv, BadValuesAreRefusedByName) {
  const std::vector<std::pair<EnvOptions, std::string>> cases = {
      {{{"bump_height", "0.06"}}, "bump_height"},
      {{{"bump_height", "-0.01"}}, "bump_height"},
      {{{"bump_height", "nan"}}, "bump_height"},
      {{{"bump_spacing", "0.1"}}, "bump_spacing"},
      {{{"bump_spacing", "11"}}, "bump_spacing"},
      {{{"bump_width", "0.001"}}, "bump_width"},
      {{{"bump_width", "0.6"}}, "bump_width"},
      {{{"bump_height", "0.02"}, {"bump_spacing", "0.5"}, {"bump_width", "0.3"}}, "bump_width"},
      // A start drawn up to 0.95 m from the origin could put a tire on the bump at 1 m.
      {{{"bump_height", "0.02"}, {"init_rand_x", "0.95"}}, "init_rand_x"},
      {{{"bump_ramp", "-1"}}, "bump_ramp"},
      {{{"bump_ramp", "11"}}, "bump_ramp"},
      {{{"bump_ramp", "nan"}}, "bump_ramp"},
      // Slopes of 10 x 2 cm each side: a footprint of 0.43 m, more than half of 0.8 m.
      {{{"bump_height", "0.02"}, {"bump_spacing", "0.8"}, {"bump_ramp", "10"}}, "bump_ramp"},
      // The slope's foot at 1 - 0.015 - 2 x 0.02 = 0.945 m: a start up to 0.9 m puts the
      // tire's front (0.95 m) past it.
      {{{"bump_height", "0.02"}, {"bump_ramp", "2"}, {"init_rand_x", "0.9"}}, "bump_ramp"},
  };
  for (const auto& [options, named] : cases) {
    const std::string message = refusal(GetParam(), options);
    EXPECT_NE(message.find(named), std::string::npos) << "\"" << message << "\"";
  }
  // Without bumps, init_rand_x is free; with them, below spacing - tire radius - width/2.
  EXPECT_EQ(refusal(GetParam(), {{"init_rand_x", "0.95"}}), "");
  EXPECT_EQ(refusal(GetParam(), {{"bump_height", "0.02"}, {"init_rand_x", "0.9"}}), "");
  EXPECT_EQ(
      refusal(GetParam(), {{"bump_height", "0.02"}, {"bump_ramp", "2"}, {"init_rand_x", "0.85"}}),
      "");
}

INSTANTIATE_TEST_SUITE_P(Engines, FloorBumpsEnv,
                         ::testing::Values("Upkie-Bullet-Velocity", "Upkie-MuJoCo-Velocity"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           return std::string(info.param).find("Bullet") != std::string::npos
                                      ? std::string("Bullet")
                                      : std::string("MuJoCo");
                         });

TEST(FloorBumpsEnv, OnlySimulatedWorldsHaveBumps) {
  for (const char* id : {"Upkie-Mock-Servos", "Upkie-Spine-Servos"}) {
    const std::string message = refusal(id, {{"bump_height", "0.02"}});
    EXPECT_NE(message.find("bump_height"), std::string::npos) << id << ": " << message;
  }
  for (const char* id : {"Upkie-Bullet-Pendulum", "Upkie-MuJoCo-Servos"}) {
    EXPECT_EQ(refusal(id, {{"bump_height", "0.02"}}), "") << id;
  }
}

}  // namespace
}  // namespace upkie_rl
