/// Each physical perturbation of PhysicsVariation changes what it should and nothing else,
/// on Bullet and on MuJoCo: the default variation is the nominal robot bit for bit, masses
/// scale the weight the legs carry, base forces push, frictions resist, noise reaches only
/// the measurements it belongs to, and a noise seed gives the same noise again.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "sim/physics_backends.hpp"
#include "sim/servo_actions.hpp"

namespace upkie_rl {
namespace {

using testing::limp_action;
using testing::pendulum_action;

constexpr double kWheelRadius = 0.05;

std::shared_ptr<const RobotModel> model() { return RobotModel::default_model(); }

struct Backend {
  const char* name;
  std::function<std::unique_ptr<PhysicsSimulation>(const PhysicsConfig&)> make;
};

using testing::make_bullet;
using testing::make_mujoco;

/// Observations of `steps` agent steps of the pendulum action at `ground_velocity`.
std::vector<Observation> run(PhysicsSimulation& simulation, int steps,
                             double ground_velocity = 0.0) {
  std::vector<Observation> observations;
  observations.push_back(simulation.reset(ResetState{}));
  for (int step = 0; step < steps; ++step) {
    observations.push_back(simulation.step(pendulum_action(ground_velocity, kWheelRadius)));
  }
  return observations;
}

bool same_motion(const Observation& a, const Observation& b) {
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    if (a.servo[servo].position != b.servo[servo].position ||
        a.servo[servo].velocity != b.servo[servo].velocity) {
      return false;
    }
  }
  return a.sim_base.position == b.sim_base.position &&
         a.sim_base.linear_velocity == b.sim_base.linear_velocity;
}

bool same_measurements(const Observation& a, const Observation& b) {
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    if (a.servo[servo].torque != b.servo[servo].torque) return false;
  }
  return a.imu.angular_velocity == b.imu.angular_velocity &&
         a.imu.linear_acceleration == b.imu.linear_acceleration &&
         a.base_orientation.angular_velocity == b.base_orientation.angular_velocity;
}

class PhysicsVariationTest : public ::testing::TestWithParam<Backend> {
 protected:
  std::unique_ptr<PhysicsSimulation> make(const PhysicsConfig& config = {}) const {
    return GetParam().make(config);
  }
};

TEST_P(PhysicsVariationTest, DefaultVariationIsTheNominalRobotBitForBit) {
  auto nominal = make();
  auto varied = make();
  // Vary, run, then set the default back: nothing of the variation may remain.
  PhysicsVariation variation;
  variation.mass_scale.fill(1.3);
  variation.floor_friction_scale = 0.5;
  variation.torque_control_noise = 0.1;
  variation.slope_pitch = 0.1;
  variation.slope_roll = -0.05;
  variation.payload_mass = 2.0;
  variation.payload_offset = Eigen::Vector3d(0.1, -0.05, 0.2);
  varied->set_variation(variation);
  run(*varied, 20, 0.3);
  varied->set_variation(PhysicsVariation{});
  const auto expected = run(*nominal, 300, 0.3);
  const auto actual = run(*varied, 300, 0.3);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    ASSERT_TRUE(same_motion(expected[i], actual[i])) << "step " << i;
    ASSERT_TRUE(same_measurements(expected[i], actual[i])) << "step " << i;
    ASSERT_EQ(expected[i].imu.orientation.coeffs(), actual[i].imu.orientation.coeffs()) << i;
    ASSERT_EQ(expected[i].imu.raw_linear_acceleration, actual[i].imu.raw_linear_acceleration) << i;
    ASSERT_EQ(expected[i].base_orientation.pitch, actual[i].base_orientation.pitch) << i;
  }
}

/// Knee torque the legs need to carry the robot, averaged from landing (0.2 s) to 0.5 s,
/// while it still stands nearly upright.
double knee_torque_standing(PhysicsSimulation& simulation) {
  const auto observations = run(simulation, 100);
  double sum = 0.0;
  for (std::size_t i = 40; i < observations.size(); ++i) {
    sum += observations[i].servo[kLeftKnee].torque;
  }
  return sum / static_cast<double>(observations.size() - 40);
}

TEST_P(PhysicsVariationTest, MassScaleScalesTheWeightTheLegsCarry) {
  auto simulation = make();
  const double nominal = knee_torque_standing(*simulation);
  ASSERT_GT(std::abs(nominal), 0.05);  // the knee does carry weight
  PhysicsVariation heavier;
  heavier.mass_scale.fill(1.5);
  simulation->set_variation(heavier);
  // Measured: 1.50 on Bullet, 1.40 on MuJoCo's tires (sliding friction in the cone, rolling
  // resistance apart): the heavier robot leans a little further over its held wheels, and
  // the knee's lever arm on straight legs is a few millimetres.
  EXPECT_NEAR(knee_torque_standing(*simulation) / nominal, 1.5, 0.12);
  // Only the wheels heavier: the knees carry what is above them, unchanged.
  PhysicsVariation heavy_wheels;
  heavy_wheels.mass_scale[1 + kLeftWheel] = 3.0;
  heavy_wheels.mass_scale[1 + kRightWheel] = 3.0;
  simulation->set_variation(heavy_wheels);
  EXPECT_NEAR(knee_torque_standing(*simulation) / nominal, 1.0, 0.12);
}

TEST_P(PhysicsVariationTest, BaseForcePushesInItsDirectionUntilReset) {
  PhysicsConfig config;
  config.floor = false;
  config.gravity = 0.0;
  auto simulation = make(config);
  simulation->reset(ResetState{});
  const Eigen::Vector3d force(20.0, -10.0, 0.0);
  simulation->set_base_force(force);
  for (int step = 0; step < 20; ++step) simulation->step(pendulum_action(0.0, kWheelRadius));
  const Eigen::Vector3d velocity = simulation->observation().sim_base.linear_velocity;
  // Momentum F t shared by the whole robot (legs held, so nearly rigid).
  // The momentum F t goes to the whole robot; the base, which the force acts on, moves
  // faster than the legs that the servos' compliance lets lag behind: between F t / m and
  // three times that.
  const Eigen::Vector3d momentum_velocity = force * 0.1 / model()->total_mass();
  for (int axis : {0, 1}) {
    const double ratio = velocity[axis] / momentum_velocity[axis];
    EXPECT_GT(ratio, 0.9) << "axis " << axis;
    EXPECT_LT(ratio, 3.0) << "axis " << axis;
  }
  EXPECT_LT(std::abs(velocity.z()), 0.1 * velocity.head<2>().norm());
  // A reset clears the force.
  simulation->reset(ResetState{});
  EXPECT_TRUE(simulation->base_force().isZero());
  for (int step = 0; step < 20; ++step) simulation->step(pendulum_action(0.0, kWheelRadius));
  EXPECT_LT(simulation->observation().sim_base.linear_velocity.norm(), 1e-3);
}

/// Left wheel velocity after spinning it up in the air and letting it coast for 0.2 s.
double coasting_wheel_velocity(PhysicsSimulation& simulation) {
  simulation.reset(ResetState{});
  for (int step = 0; step < 20; ++step) simulation.step(pendulum_action(0.5, kWheelRadius));
  for (int step = 0; step < 40; ++step) simulation.step(limp_action());
  return simulation.observation().servo[kLeftWheel].velocity;
}

TEST_P(PhysicsVariationTest, JointFrictionSlowsACoastingWheel) {
  PhysicsConfig config;
  config.floor = false;
  config.gravity = 0.0;
  auto simulation = make(config);
  const double free = coasting_wheel_velocity(*simulation);
  ASSERT_GT(free, 5.0);
  PhysicsVariation variation;
  variation.joint_friction[kLeftWheel] = 0.005;
  simulation->set_variation(variation);
  const double braked = coasting_wheel_velocity(*simulation);
  EXPECT_LT(braked, free - 1.0);
  EXPECT_GE(braked, -1e-2);  // kinetic friction stops a wheel, never reverses it
  // The other wheel has no friction: it coasts as before.
  EXPECT_NEAR(simulation->observation().servo[kRightWheel].velocity, -free, 0.05 * free);
}

TEST_P(PhysicsVariationTest, TorqueMeasurementNoiseChangesOnlyObservedTorques) {
  auto nominal = make();
  auto noisy = make();
  PhysicsVariation variation;
  variation.torque_measurement_noise = 0.2;
  variation.noise_seed = 7;
  noisy->set_variation(variation);
  const auto expected = run(*nominal, 100);
  const auto actual = run(*noisy, 100);
  double squared = 0.0;
  for (std::size_t i = 1; i < expected.size(); ++i) {
    ASSERT_TRUE(same_motion(expected[i], actual[i])) << "step " << i;
    const double error = actual[i].servo[kLeftKnee].torque - expected[i].servo[kLeftKnee].torque;
    squared += error * error;
  }
  EXPECT_NEAR(std::sqrt(squared / 100.0), 0.2, 0.06);
}

TEST_P(PhysicsVariationTest, TorqueControlNoiseMovesTheRobot) {
  auto nominal = make();
  auto noisy = make();
  PhysicsVariation variation;
  variation.torque_control_noise = 0.5;
  noisy->set_variation(variation);
  const auto expected = run(*nominal, 100);
  const auto actual = run(*noisy, 100);
  EXPECT_FALSE(same_motion(expected.back(), actual.back()));
}

// A weaker motor: a knee told to go 2 rad away saturates at its effort, times the scale.
TEST_P(PhysicsVariationTest, TorqueLimitScaleCapsTheServoTorque) {
  const double effort = model()->servo_limits(kLeftKnee).effort;
  const auto saturated_torque = [](PhysicsSimulation& simulation) {
    simulation.reset(ResetState{});
    ServoAction action = pendulum_action(0.0, kWheelRadius);
    action[kLeftKnee].position += 2.0;
    return simulation.step(action).servo[kLeftKnee].torque;
  };
  auto simulation = make();
  EXPECT_NEAR(std::abs(saturated_torque(*simulation)), effort, 1e-9);
  PhysicsVariation weaker;
  weaker.torque_limit_scale = 0.8;
  simulation->set_variation(weaker);
  EXPECT_NEAR(std::abs(saturated_torque(*simulation)), 0.8 * effort, 1e-9);
  weaker.torque_limit_scale = 0.0;
  EXPECT_THROW(simulation->set_variation(weaker), std::invalid_argument);
}

// A knee told to go 0.2 rad away, in the air: with its gains scaled up it moves further in
// the first step (torque kp·scale·error, well below its limit), scaled down less far.
TEST_P(PhysicsVariationTest, ServoGainScaleScalesTheServoLaw) {
  PhysicsConfig config;
  config.floor = false;
  config.gravity = 0.0;
  auto simulation = make(config);
  const auto knee_motion = [&](double scale) {
    PhysicsVariation variation;
    variation.servo_gain_scale[kLeftKnee] = scale;
    simulation->set_variation(variation);
    simulation->reset(ResetState{});
    ServoAction action = pendulum_action(0.0, kWheelRadius);
    action[kLeftKnee].position += 0.2;
    return simulation->step(action).servo[kLeftKnee].position;
  };
  const double nominal = knee_motion(1.0);
  ASSERT_GT(nominal, 1e-4);
  EXPECT_GT(knee_motion(2.0), 1.25 * nominal);  // not twice: kd scales too, and damps
  EXPECT_LT(knee_motion(0.5), 0.75 * nominal);
  PhysicsVariation zero;
  zero.servo_gain_scale[kLeftKnee] = 0.0;
  EXPECT_THROW(simulation->set_variation(zero), std::invalid_argument);
}

TEST_P(PhysicsVariationTest, ImuBiasReachesTheImuAndThePitchRateOnly) {
  auto nominal = make();
  auto biased = make();
  PhysicsVariation variation;
  variation.imu.gyroscope_bias = Eigen::Vector3d(0.0, 0.1, 0.0);
  variation.imu.accelerometer_bias = Eigen::Vector3d(0.3, 0.0, 0.0);
  biased->set_variation(variation);
  const auto expected = run(*nominal, 50);
  const auto actual = run(*biased, 50);
  const Eigen::Matrix3d base_to_imu = model()->rotation_base_to_imu();
  for (std::size_t i = 0; i < expected.size(); ++i) {
    ASSERT_TRUE(same_motion(expected[i], actual[i])) << "step " << i;
    EXPECT_TRUE((actual[i].imu.angular_velocity - expected[i].imu.angular_velocity)
                    .isApprox(variation.imu.gyroscope_bias, 1e-9));
    EXPECT_TRUE((actual[i].imu.linear_acceleration - expected[i].imu.linear_acceleration)
                    .isApprox(variation.imu.accelerometer_bias, 1e-9));
    EXPECT_TRUE((actual[i].base_orientation.angular_velocity -
                 expected[i].base_orientation.angular_velocity)
                    .isApprox(base_to_imu * variation.imu.gyroscope_bias, 1e-9));
    EXPECT_EQ(actual[i].base_orientation.pitch, expected[i].base_orientation.pitch);
  }
}

TEST_P(PhysicsVariationTest, OnASlipperyFloorBrakedWheelsSlide) {
  // The robot starts on the floor moving forward at 0.5 m/s with its wheels braked. The
  // floor's friction is the only horizontal force: with grip it stops the wheels' contact
  // and tips the robot; on a slippery floor (at most 0.02 g of deceleration) it coasts.
  const auto velocity_after_50ms = [&](double friction_scale) {
    auto simulation = make();
    PhysicsVariation variation;
    variation.floor_friction_scale = friction_scale;
    simulation->set_variation(variation);
    ResetState state;
    state.position_base_in_world.z() -= 0.0425;  // tires on the floor
    state.linear_velocity_base_to_world_in_world.x() = 0.5;
    simulation->reset(state);
    ServoAction braked = pendulum_action(0.0, kWheelRadius);
    braked[kLeftWheel].kd_scale = braked[kRightWheel].kd_scale = 5.0;
    for (int step = 0; step < 10; ++step) simulation->step(braked);
    return simulation->observation().sim_base.linear_velocity.x();
  };
  EXPECT_NEAR(velocity_after_50ms(0.02), 0.5, 0.03);
  EXPECT_GT(std::abs(velocity_after_50ms(1.0) - 0.5), 0.1);
}

TEST_P(PhysicsVariationTest, NoiseSeedGivesTheSameNoise) {
  PhysicsVariation variation;
  variation.torque_control_noise = 0.3;
  variation.imu.gyroscope_noise = 0.05;
  variation.noise_seed = 11;
  auto first = make();
  auto second = make();
  first->set_variation(variation);
  second->set_variation(variation);
  const auto a = run(*first, 100);
  const auto b = run(*second, 100);
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_TRUE(same_motion(a[i], b[i]) && same_measurements(a[i], b[i])) << "step " << i;
  }
  variation.noise_seed = 12;
  second->set_variation(variation);
  EXPECT_FALSE(same_measurements(run(*second, 100).back(), a.back()));
}

TEST_P(PhysicsVariationTest, BadVariationIsRefusedAndChangesNothing) {
  auto simulation = make();
  PhysicsVariation bad;
  bad.mass_scale[3] = -1.0;
  EXPECT_THROW(
      {
        try {
          simulation->set_variation(bad);
        } catch (const std::invalid_argument& error) {
          EXPECT_NE(std::string(error.what()).find("mass_scale[3]"), std::string::npos);
          throw;
        }
      },
      std::invalid_argument);
  bad = PhysicsVariation{};
  bad.imu.gyroscope_noise = std::nan("");
  EXPECT_THROW(simulation->set_variation(bad), std::invalid_argument);
  EXPECT_THROW(simulation->set_base_force(Eigen::Vector3d(1.0, INFINITY, 0.0)),
               std::invalid_argument);
  EXPECT_FALSE(simulation->variation().changes_model());
  EXPECT_TRUE(simulation->base_force().isZero());
}

INSTANTIATE_TEST_SUITE_P(Engines, PhysicsVariationTest,
                         ::testing::Values(Backend{"Bullet", make_bullet},
                                           Backend{"MuJoCo", make_mujoco}),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace upkie_rl
