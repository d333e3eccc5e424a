/// Floor slopes (PhysicsVariation::slope_pitch, slope_roll), simulated as a flat floor under
/// tilted gravity, on Bullet and on MuJoCo: gravity points down the slope of the robot's
/// initial heading, a robot slides and rolls downhill as Coulomb's and Newton's laws say,
/// and its IMU reads what it would read on a real slope (attitude relative to gravity).

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "model/rigid_body_tree.hpp"
#include "sim/floor_slope.hpp"
#include "sim/physics_backends.hpp"
#include "sim/servo_actions.hpp"

namespace upkie_rl {
namespace {

using testing::make_bullet;
using testing::make_mujoco;

/// MuJoCo without the tires' rolling resistance: they roll freely, which shows the slope's
/// pull on its own.
std::unique_ptr<PhysicsSimulation> make_free_rolling_mujoco(const PhysicsConfig& physics) {
  MujocoConfig config;
  static_cast<PhysicsConfig&>(config) = physics;
  config.tire_rolling_resistance = false;
  return std::make_unique<MujocoSimulation>(RobotModel::default_model(), config);
}
using testing::pendulum_action;

constexpr double kGravity = 9.81;
/// Wheel axles below the base origin with straight legs [m]: the URDF's tire centres are
/// at z = -0.507 in the base frame at q = 0 (the base stands 0.557 m high on 0.05 m tires).
constexpr double kAxleDepth = 0.507;
/// Tires start this far above the floor [m]: the robot settles on them within 10 ms.
constexpr double kTireClearance = 5e-4;

double degrees(double value) { return degrees_to_radians(value); }

// ---------------------------------------------------------------------------------------
// The geometry of a slope, on its own.

TEST(FloorSlope, AFlatFloorIsExactlyTheNominalGravity) {
  const FloorSlope flat = make_floor_slope(0.0, 0.0, 1.3, kGravity);
  EXPECT_FALSE(flat.tilted);
  EXPECT_EQ(flat.gravity_in_floor, Eigen::Vector3d(0.0, 0.0, -kGravity));
  EXPECT_EQ(flat.rotation_floor_to_level, Eigen::Matrix3d::Identity());
}

TEST(FloorSlope, GravityPullsDownTheSlopeOfTheInitialHeading) {
  const double angle = degrees(8.0);
  const double along = kGravity * std::sin(angle);
  const double normal = -kGravity * std::cos(angle);
  // Facing uphill along x: pulled backward.
  EXPECT_TRUE(make_floor_slope(angle, 0.0, 0.0, kGravity)
                  .gravity_in_floor.isApprox(Eigen::Vector3d(-along, 0.0, normal), 1e-12));
  // Heading +y (yaw 90 degrees): pulled toward -y, the robot's backward.
  EXPECT_TRUE(make_floor_slope(angle, 0.0, M_PI / 2.0, kGravity)
                  .gravity_in_floor.isApprox(Eigen::Vector3d(0.0, -along, normal), 1e-12));
  // Roll: the floor rises to the robot's left, gravity pulls it to its right.
  EXPECT_TRUE(make_floor_slope(0.0, angle, 0.0, kGravity)
                  .gravity_in_floor.isApprox(Eigen::Vector3d(0.0, -along, normal), 1e-12));
  // Both at once: the magnitude stays g, the floor normal component is cos·cos.
  const FloorSlope both = make_floor_slope(angle, -angle, 0.4, kGravity);
  EXPECT_TRUE(both.tilted);
  EXPECT_NEAR(both.gravity_in_floor.norm(), kGravity, 1e-12);
  EXPECT_NEAR(both.gravity_in_floor.z(), normal * std::cos(angle), 1e-12);
  EXPECT_NEAR(both.rotation_floor_to_level.determinant(), 1.0, 1e-12);
}

// ---------------------------------------------------------------------------------------
// The engines.

/// One backend under test.
struct Backend {
  const char* name;
  std::function<std::unique_ptr<PhysicsSimulation>(const PhysicsConfig&)> make;
  /// Whether the tires roll freely. Bullet's do not: the reference tires' rolling friction
  /// (0.01 m: a torque of up to 0.01 m times the normal force, i.e. a resistance of 0.2 of
  /// the weight at r = 0.05 m) holds a robot with free wheels on every slope up to 15 deg;
  /// MuJoCo's have the same resistance (MujocoConfig::tire_rolling_resistance), and roll
  /// freely without it ("MuJoCoFreeRolling", which checks the slope's physics).
  bool tires_roll_freely;
};

class FloorSlopeEngine : public ::testing::TestWithParam<Backend> {
 protected:
  std::unique_ptr<PhysicsSimulation> make(const PhysicsConfig& config = {}) const {
    return GetParam().make(config);
  }
};

/// A state with the tires just above the floor and the base turned by `orientation` about
/// the wheel axle.
ResetState on_the_floor(const Eigen::Quaterniond& orientation, double wheel_radius) {
  ResetState state;
  state.orientation_base_in_world = orientation;
  state.position_base_in_world = Eigen::Vector3d(0.0, 0.0, wheel_radius + kTireClearance) +
                                 orientation * Eigen::Vector3d(0.0, 0.0, kAxleDepth);
  return state;
}

/// Legs held straight by their servos; the wheels braked (a stiff velocity loop at 0) or
/// free (no torque at all).
ServoAction hold_legs(bool brake_wheels, double wheel_radius) {
  ServoAction action = pendulum_action(0.0, wheel_radius);
  for (const std::size_t wheel : {kLeftWheel, kRightWheel}) {
    action[wheel].kp_scale = 0.0;
    action[wheel].kd_scale = brake_wheels ? 5.0 : 0.0;
  }
  return action;
}

/// Mean acceleration of the robot's centre of mass [m/s^2] from 0.05 s (the tires have
/// settled on the floor) to 0.15 s (the body, an inverted pendulum, has not yet tipped far),
/// from centre-of-mass velocities differenced over two agent steps.
Eigen::Vector3d com_acceleration(PhysicsSimulation& simulation, const ResetState& state,
                                 const ServoAction& action) {
  simulation.reset(state);
  std::vector<Eigen::Vector3d> com{simulation.mass_distribution().center_of_mass};
  for (int step = 0; step < 31; ++step) {
    simulation.step(action);
    com.push_back(simulation.mass_distribution().center_of_mass);
  }
  const double dt = simulation.agent_timestep();
  const auto velocity = [&](int step) { return (com[step + 1] - com[step - 1]) / (2.0 * dt); };
  return (velocity(30) - velocity(10)) / (20.0 * dt);
}

/// One slope of a test: angles [deg] and the direction downhill in the floor frame.
struct Slope {
  double pitch;
  double roll;
  Eigen::Vector3d downhill;
  double angle() const { return degrees(pitch != 0.0 ? pitch : roll); }
};

const std::vector<Slope> kSlopes = {
    {8.0, 0.0, -Eigen::Vector3d::UnitX()},  {15.0, 0.0, -Eigen::Vector3d::UnitX()},
    {-8.0, 0.0, Eigen::Vector3d::UnitX()},  {0.0, 8.0, -Eigen::Vector3d::UnitY()},
    {0.0, 15.0, -Eigen::Vector3d::UnitY()}, {0.0, -8.0, Eigen::Vector3d::UnitY()}};

/// On a pitch slope the robot starts upright against gravity (tilted about its axle); on a
/// roll slope, upright on the floor (both tires down).
ResetState start_on(const Slope& slope, double wheel_radius) {
  return on_the_floor(
      Eigen::Quaterniond(Eigen::AngleAxisd(degrees(slope.pitch), Eigen::Vector3d::UnitY())),
      wheel_radius);
}

PhysicsVariation slope_variation(const Slope& slope, double floor_friction_scale) {
  PhysicsVariation variation;
  variation.slope_pitch = degrees(slope.pitch);
  variation.slope_roll = degrees(slope.roll);
  variation.floor_friction_scale = floor_friction_scale;
  return variation;
}

TEST_P(FloorSlopeEngine, OnASlipperyFloorBrakedWheelsSlideDownhillByCoulombsLaw) {
  // Tire friction 0.05 (tan 8 deg = 0.14): the braked robot slides, and the floor's only
  // force along it is kinetic friction, mu times the normal force. The whole robot's
  // centre of mass then accelerates downhill at g (sin θ - mu cos θ), whatever its body
  // does: 0.88 m/s^2 at 8 deg, 2.07 at 15. Across the slope (roll) the robot does not tip:
  // measured within 3% of it on both engines. Along it (pitch) the friction below the
  // centre of mass tips the body downhill, its centre of mass drops and the tires carry
  // less than the weight, so less friction: measured 3-7% more on MuJoCo, 5-14% on Bullet.
  constexpr double kFriction = 0.05;
  auto simulation = make();
  const double radius = simulation->model().wheel_radius();
  for (const Slope& slope : kSlopes) {
    simulation->set_variation(slope_variation(slope, kFriction));
    const Eigen::Vector3d acceleration =
        com_acceleration(*simulation, start_on(slope, radius), hold_legs(true, radius));
    const double angle = std::abs(slope.angle());
    const double expected = kGravity * (std::sin(angle) - kFriction * std::cos(angle));
    const double ratio = acceleration.dot(slope.downhill) / expected;
    const double across =
        std::abs(acceleration.dot(slope.downhill.cross(Eigen::Vector3d::UnitZ())));
    const std::string name =
        "pitch " + std::to_string(slope.pitch) + " roll " + std::to_string(slope.roll);
    EXPECT_GT(ratio, 0.97) << name;
    // Roll slopes: 1.00 on Bullet, 1.05 on MuJoCo (the rolling resistance's torque, about
    // the wheel axis, tips the braked robot a little down the slope).
    EXPECT_LT(ratio, slope.pitch != 0.0 ? 1.16 : 1.06) << name;
    EXPECT_LT(across, 0.05 * expected) << name;
  }
}

/// Spin inertia of the wheel `wheel` about its axle [kg.m^2], from the rigid bodies the
/// engines simulate.
double wheel_spin_inertia(const RobotModel& model, std::size_t wheel) {
  const RigidBodyTree tree(model, InertiaSource::kBulletBoxRule, /*merge_fixed_links=*/true);
  const RigidBody& body = tree.bodies()[tree.servo_body(wheel)];
  const Eigen::Matrix3d axes = body.principal_frame.linear();
  const Eigen::Matrix3d inertia = axes * body.principal_inertia.asDiagonal() * axes.transpose();
  const Eigen::Vector3d axis = body.joint_axis.normalized();
  const Eigen::Vector3d com = body.principal_frame.translation();
  const Eigen::Vector3d off_axis = com - com.dot(axis) * axis;
  return axis.dot(inertia * axis) + body.mass * off_axis.squaredNorm();
}

TEST_P(FloorSlopeEngine, FreeWheelsRollDownhill) {
  // Wheels free (no torque), tires gripping (friction 1): the floor's force along the
  // slope is what spins the wheels, I_w a_axle / r^2. A rigid robot would accelerate at
  // g sin θ m / (m + I_w / r^2) (0.962 g sin θ here); the body, free to pitch about the
  // axle, lets the axle run ahead of the centre of mass (a planar two-body model: about 3
  // times), which leaves 0.89 g sin θ = 0.925 of the rigid value (measured on MuJoCo:
  // 0.88 at 8 deg, 0.91 at 15, 0.90 at -8): expected in [0.85, 1.0] of it, the same share
  // within 5% on every slope, so that the acceleration scales with sin θ.
  auto simulation = make();
  const RobotModel& model = simulation->model();
  const double radius = model.wheel_radius();
  const double mass = simulation->mass_distribution().total_mass;
  const double wheels_inertia =
      wheel_spin_inertia(model, kLeftWheel) + wheel_spin_inertia(model, kRightWheel);
  const double rigid_factor = mass / (mass + wheels_inertia / (radius * radius));
  ASSERT_NEAR(rigid_factor, 0.962, 0.01);
  // On the flat floor the body's fall alone moves the centre of mass (Bullet: 0.2 m/s^2
  // backward, its tires resisting the roll): slopes are compared with it.
  const Eigen::Vector3d flat =
      com_acceleration(*simulation, start_on({0.0, 0.0, {}}, radius), hold_legs(false, radius));
  std::vector<double> ratios;
  for (const Slope& slope : kSlopes) {
    if (slope.pitch == 0.0) continue;  // a wheel does not roll sideways
    simulation->set_variation(slope_variation(slope, 1.0));
    const Eigen::Vector3d acceleration =
        com_acceleration(*simulation, start_on(slope, radius), hold_legs(false, radius));
    const double rigid = kGravity * std::sin(std::abs(slope.angle())) * rigid_factor;
    const double ratio = (acceleration - flat).dot(slope.downhill) / rigid;
    ratios.push_back(ratio);
    if (GetParam().tires_roll_freely) {
      EXPECT_GT(ratio, 0.85) << "pitch " << slope.pitch;
      EXPECT_LT(ratio, 1.0) << "pitch " << slope.pitch;
    } else {
      // Held: measured within 19% of the free roll (Bullet -0.04, -0.02, -0.14; MuJoCo -0.01,
      // 0.19, -0.01: its resistance grows in proportion below 0.1 rad/s, so a wheel creeps
      // on the steepest slope), the difference the body's fall makes facing downhill rather
      // than uphill.
      EXPECT_LT(std::abs(ratio), 0.2) << "pitch " << slope.pitch;
    }
  }
  if (GetParam().tires_roll_freely) {
    // The pendulum's coupling changes with cos θ (2% from 8 to 15 deg), and the body's
    // centre of mass, 6 mm behind the axle, starts its fall backward whichever way the
    // robot faces.
    EXPECT_NEAR(ratios[1] / ratios[0], 1.0, 0.05);
    EXPECT_NEAR(ratios[2] / ratios[0], 1.0, 0.05);
  }
}

TEST_P(FloorSlopeEngine, OnAGrippingFloorARollSlopeDoesNotMoveTheRobotSideways) {
  // Tire friction 1 > tan 15 deg: the tires hold the robot across the slope, and its
  // centre of mass, 0.31 m above the floor between tires 0.30 m apart, stays within their
  // track up to 26 deg: it neither slides nor tips. Bullet's friction constraints are
  // soft (friction ERP 0.2) and let the tires creep: measured 3% of g sin θ at 15 deg,
  // MuJoCo's 0.3%; the slippery floor above slides at 100%.
  auto simulation = make();
  const double radius = simulation->model().wheel_radius();
  for (const double roll : {8.0, 15.0, -15.0}) {
    const Slope slope{0.0, roll, {}};
    simulation->set_variation(slope_variation(slope, 1.0));
    const Eigen::Vector3d acceleration =
        com_acceleration(*simulation, start_on(slope, radius), hold_legs(true, radius));
    EXPECT_LT(std::abs(acceleration.y()), 0.05 * kGravity * std::sin(degrees(std::abs(roll))))
        << "roll " << roll;
  }
}

TEST_P(FloorSlopeEngine, TheImuReadsTheAttitudeOfARealSlope) {
  // A robot upright on an 8 deg slope, facing uphill, leans back 8 deg from the vertical:
  // its IMU and attitude read a pitch of -8 deg, as they would on a real slope, while the
  // ground truth (sim.base, in the floor's frame) stays upright.
  auto simulation = make();
  PhysicsVariation variation;
  variation.slope_pitch = degrees(8.0);
  simulation->set_variation(variation);
  const Observation& observation = simulation->reset(ResetState{});
  EXPECT_NEAR(observation.base_orientation.pitch, -degrees(8.0), 1e-12);
  EXPECT_TRUE(observation.sim_base.orientation.isApprox(Eigen::Quaterniond::Identity(), 1e-12));
  // The accelerometer at rest reads +g along the vertical, which points 8 deg ahead of the
  // base's z: in the IMU frame (x backward, z down), (-g sin 8, 0, -g cos 8).
  EXPECT_TRUE(observation.imu.raw_linear_acceleration.isApprox(
      Eigen::Vector3d(-kGravity * std::sin(degrees(8.0)), 0.0, -kGravity * std::cos(degrees(8.0))),
      1e-9));
  // Across the slope: a roll of +8 deg (left side up), no pitch.
  variation.slope_pitch = 0.0;
  variation.slope_roll = degrees(8.0);
  simulation->set_variation(variation);
  simulation->reset(ResetState{});
  const Eigen::Matrix3d& rotation = observation.base_orientation.rotation_base_to_world;
  EXPECT_NEAR(std::atan2(rotation(2, 1), rotation(2, 2)), degrees(8.0), 1e-12);
  EXPECT_NEAR(observation.base_orientation.pitch, 0.0, 1e-12);
}

/// Observations of `steps` agent steps from `state`, legs held.
std::vector<Observation> fall(PhysicsSimulation& simulation, const ResetState& state, int steps) {
  std::vector<Observation> observations{simulation.reset(state)};
  const ServoAction action = pendulum_action(0.0, simulation.model().wheel_radius());
  for (int step = 0; step < steps; ++step) observations.push_back(simulation.step(action));
  return observations;
}

TEST_P(FloorSlopeEngine, UnderTiltedGravityTheImuReadsWhatATiltedRobotReads) {
  // Without a floor, a robot upright under gravity tilted by the slope moves exactly as a
  // robot tilted the other way under vertical gravity: every IMU and attitude reading must
  // be the same (to rounding), accelerometer included.
  PhysicsConfig config;
  config.floor = false;
  auto sloped = make(config);
  auto tilted = make(config);
  PhysicsVariation variation;
  variation.slope_pitch = degrees(10.0);
  variation.slope_roll = degrees(-6.0);
  sloped->set_variation(variation);
  const double heading = 0.6;
  ResetState upright;
  upright.orientation_base_in_world = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ());
  upright.angular_velocity_base_in_base = Eigen::Vector3d(0.3, -0.5, 0.2);  // base frame
  const auto expected_slope =
      make_floor_slope(variation.slope_pitch, variation.slope_roll, heading, config.gravity);
  ResetState leaning = upright;
  leaning.orientation_base_in_world = Eigen::Quaterniond(expected_slope.rotation_floor_to_level) *
                                      upright.orientation_base_in_world;
  const auto a = fall(*sloped, upright, 30);
  const auto b = fall(*tilted, leaning, 30);
  EXPECT_TRUE(sloped->floor_slope().gravity_in_floor.isApprox(expected_slope.gravity_in_floor));
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a[i].base_orientation.pitch, b[i].base_orientation.pitch, 1e-9) << i;
    EXPECT_TRUE(a[i].base_orientation.rotation_base_to_world.isApprox(
        b[i].base_orientation.rotation_base_to_world, 1e-9))
        << i;
    EXPECT_TRUE(a[i].imu.orientation.isApprox(b[i].imu.orientation, 1e-9)) << i;
    EXPECT_LT((a[i].imu.angular_velocity - b[i].imu.angular_velocity).norm(), 1e-6) << i;
    EXPECT_LT((a[i].imu.raw_linear_acceleration - b[i].imu.raw_linear_acceleration).norm(), 1e-4)
        << i;
    EXPECT_LT((a[i].imu.linear_acceleration - b[i].imu.linear_acceleration).norm(), 1e-4) << i;
  }
  // The attitude did change along the way (the comparison is not of constants).
  EXPECT_GT(std::abs(a.back().base_orientation.pitch - a.front().base_orientation.pitch), 0.05);
}

TEST_P(FloorSlopeEngine, BadSlopesAreRefusedNamingThem) {
  auto simulation = make();
  const auto message = [&](const PhysicsVariation& variation) {
    try {
      simulation->set_variation(variation);
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string();
  };
  PhysicsVariation variation;
  variation.slope_pitch = degrees(15.5);
  EXPECT_NE(message(variation).find("slope_pitch"), std::string::npos);
  variation.slope_pitch = degrees(-15.0);  // the bound itself is a slope
  EXPECT_EQ(message(variation), "");
  variation.slope_roll = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message(variation).find("slope_roll"), std::string::npos);
  EXPECT_EQ(simulation->variation().slope_roll, 0.0);  // a refused variation changes nothing
}

INSTANTIATE_TEST_SUITE_P(
    Engines, FloorSlopeEngine,
    ::testing::Values(Backend{"Bullet", make_bullet, false}, Backend{"MuJoCo", make_mujoco, false},
                      Backend{"MuJoCoFreeRolling", make_free_rolling_mujoco, true}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace upkie_rl
