/// A payload (PhysicsVariation::payload_mass, payload_offset): a point mass rigidly attached
/// to the base. The mass properties it gives (parallel axis theorem), then on Bullet and on
/// MuJoCo: the base body and the whole robot weigh it and have their centres of mass moved
/// by it, as read back from each engine's model, and it moves the robot as it should.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "sim/mass_properties.hpp"
#include "sim/physics_backends.hpp"
#include "sim/servo_actions.hpp"

namespace upkie_rl {
namespace {

using testing::make_bullet;
using testing::make_mujoco;
using testing::pendulum_action;

/// Inertia of a point mass about the origin of `offset`.
Eigen::Matrix3d point_inertia(double mass, const Eigen::Vector3d& offset) {
  return mass * (offset.squaredNorm() * Eigen::Matrix3d::Identity() - offset * offset.transpose());
}

/// The tensor of `properties` about its centre of mass, expressed as its inertia_in_body,
/// must be a rotation of its principal moments.
void expect_proper_principal_frame(const MassProperties& properties) {
  const Eigen::Matrix3d axes = properties.principal_frame.linear();
  EXPECT_TRUE((axes.transpose() * axes).isApprox(Eigen::Matrix3d::Identity(), 1e-12));
  EXPECT_NEAR(axes.determinant(), 1.0, 1e-12);
}

TEST(MassProperties, APointMassOnAPrincipalAxisKeepsTheAxes) {
  // 2 kg at the origin, moments (1, 2, 3); 1 kg at x = 0.3: centre of mass at x = 0.1.
  // About it: the body 0.1 m away, the point 0.2 m away, both along x.
  MassProperties body;
  body.mass = 2.0;
  body.principal_inertia = Eigen::Vector3d(1.0, 2.0, 3.0);
  const MassProperties result = with_point_mass(body, 1.0, Eigen::Vector3d(0.3, 0.0, 0.0));
  EXPECT_DOUBLE_EQ(result.mass, 3.0);
  EXPECT_TRUE(result.principal_frame.translation().isApprox(Eigen::Vector3d(0.1, 0.0, 0.0)));
  EXPECT_TRUE(result.principal_frame.linear().isIdentity(0.0));
  EXPECT_TRUE(result.principal_inertia.isApprox(
      Eigen::Vector3d(1.0, 2.0 + 2.0 * 0.01 + 0.04, 3.0 + 2.0 * 0.01 + 0.04), 1e-12));
}

TEST(MassProperties, AnyPointMassFollowsTheParallelAxisTheorem) {
  MassProperties body;
  body.mass = 3.5;
  body.principal_frame.linear() =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
  body.principal_frame.translation() = Eigen::Vector3d(0.01, -0.02, 0.1);
  body.principal_inertia = Eigen::Vector3d(0.02, 0.03, 0.015);
  const double mass = 2.0;
  const Eigen::Vector3d position(0.15, -0.1, 0.25);
  const MassProperties result = with_point_mass(body, mass, position);
  const Eigen::Vector3d com =
      (body.mass * body.principal_frame.translation() + mass * position) / (body.mass + mass);
  const Eigen::Matrix3d expected =
      body.inertia_in_body() + point_inertia(body.mass, body.principal_frame.translation() - com) +
      point_inertia(mass, position - com);
  EXPECT_NEAR(result.mass, 5.5, 1e-15);
  EXPECT_TRUE(result.principal_frame.translation().isApprox(com, 1e-15));
  EXPECT_TRUE(result.inertia_in_body().isApprox(expected, 1e-12));
  expect_proper_principal_frame(result);
}

// ---------------------------------------------------------------------------------------
// The engines.

struct Backend {
  const char* name;
  std::function<std::unique_ptr<PhysicsSimulation>(const PhysicsConfig&)> make;
};

class PayloadEngine : public ::testing::TestWithParam<Backend> {
 protected:
  std::unique_ptr<PhysicsSimulation> make(const PhysicsConfig& config = {}) const {
    return GetParam().make(config);
  }
};

PhysicsVariation payload(double mass, const Eigen::Vector3d& offset) {
  PhysicsVariation variation;
  variation.payload_mass = mass;
  variation.payload_offset = offset;
  return variation;
}

TEST_P(PayloadEngine, ThePayloadAddsItsMassAtItsOffset) {
  // The default reset: base upright at the origin of the floor frame, so the base frame's
  // axes are the world's.
  auto simulation = make();
  const RobotMassDistribution nominal = simulation->mass_distribution();
  for (const auto& [mass, offset] : {std::pair{2.0, Eigen::Vector3d(0.1, -0.05, 0.15)},
                                     std::pair{3.0, Eigen::Vector3d(-0.2, 0.2, -0.2)},
                                     std::pair{0.5, Eigen::Vector3d::Zero().eval()}}) {
    simulation->set_variation(payload(mass, offset));
    simulation->reset(ResetState{});
    const RobotMassDistribution varied = simulation->mass_distribution();
    const MassProperties& base = nominal.base;
    const Eigen::Vector3d base_com = base.principal_frame.translation();
    // The base body: its mass plus the payload, its centre of mass moved toward it by
    // mass·offset / (base mass + mass), its inertia about the new centre of mass.
    EXPECT_NEAR(varied.base.mass, base.mass + mass, 1e-12);
    EXPECT_TRUE(varied.base.principal_frame.translation().isApprox(
        base_com + mass * offset / (base.mass + mass), 1e-12));
    const Eigen::Matrix3d expected_inertia =
        base.inertia_in_body() + point_inertia(base.mass, -mass * offset / (base.mass + mass)) +
        point_inertia(mass, base.mass * offset / (base.mass + mass));
    EXPECT_TRUE(varied.base.inertia_in_body().isApprox(expected_inertia, 1e-9));
    expect_proper_principal_frame(varied.base);
    // The whole robot: the payload at base_com + offset (world = base frame here) moves its
    // centre of mass by mass·(that point - the centre of mass) / (total + mass).
    const Eigen::Vector3d payload_in_world =
        ResetState{}.position_base_in_world + base_com + offset;
    EXPECT_NEAR(varied.total_mass, nominal.total_mass + mass, 1e-12);
    EXPECT_TRUE((varied.center_of_mass - nominal.center_of_mass)
                    .isApprox(mass * (payload_in_world - nominal.center_of_mass) /
                                  (nominal.total_mass + mass),
                              1e-9))
        << "payload " << mass << " kg at " << offset.transpose();
  }
  // Without payload again: the nominal robot.
  simulation->set_variation(PhysicsVariation{});
  simulation->reset(ResetState{});
  EXPECT_EQ(simulation->mass_distribution().base.mass, nominal.base.mass);
  EXPECT_EQ(simulation->mass_distribution().center_of_mass, nominal.center_of_mass);
}

TEST_P(PayloadEngine, TheMassScaleDoesNotScaleThePayload) {
  auto simulation = make();
  const double base_mass = simulation->mass_distribution().base.mass;
  PhysicsVariation variation = payload(1.5, Eigen::Vector3d(0.0, 0.0, 0.1));
  variation.mass_scale.fill(2.0);
  simulation->set_variation(variation);
  simulation->reset(ResetState{});
  EXPECT_NEAR(simulation->mass_distribution().base.mass, 2.0 * base_mass + 1.5, 1e-12);
}

/// Pitch [rad] of the robot after 0.6 s on the floor, legs held, wheels holding still.
double pitch_after_standing(PhysicsSimulation& simulation) {
  simulation.reset(ResetState{});
  const ServoAction action = pendulum_action(0.0, simulation.model().wheel_radius());
  for (int step = 0; step < 120; ++step) simulation.step(action);
  return simulation.observation().base_orientation.pitch;
}

TEST_P(PayloadEngine, AForwardPayloadTipsTheRobotForward) {
  // The nominal robot's centre of mass is 6 mm behind its axle: left to itself it tips
  // backward. 3 kg 0.2 m ahead of the base's centre of mass bring the whole robot's 7 cm
  // ahead of the axle: it tips forward, and faster than the nominal robot tips back.
  auto simulation = make();
  const double nominal = pitch_after_standing(*simulation);
  simulation->set_variation(payload(3.0, Eigen::Vector3d(0.2, 0.0, 0.0)));
  const double loaded = pitch_after_standing(*simulation);
  EXPECT_LT(nominal, 0.0);
  EXPECT_GT(loaded, std::abs(nominal));
}

TEST_P(PayloadEngine, BadPayloadsAreRefusedNamingThem) {
  auto simulation = make();
  const auto message = [&](const PhysicsVariation& variation) {
    try {
      simulation->set_variation(variation);
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string();
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message(payload(-0.1, Eigen::Vector3d::Zero())).find("payload_mass"),
            std::string::npos);
  EXPECT_NE(message(payload(nan, Eigen::Vector3d::Zero())).find("payload_mass"), std::string::npos);
  EXPECT_NE(message(payload(3.5, Eigen::Vector3d::Zero())).find("payload_mass"), std::string::npos);
  EXPECT_NE(message(payload(1.0, Eigen::Vector3d(0.0, 0.25, 0.0))).find("payload_offset_y"),
            std::string::npos);
  EXPECT_NE(message(payload(1.0, Eigen::Vector3d(0.0, 0.0, nan))).find("payload_offset_z"),
            std::string::npos);
  EXPECT_EQ(message(payload(3.0, Eigen::Vector3d(-0.2, 0.2, 0.2))), "");  // the bounds
  simulation->set_variation(PhysicsVariation{});
  EXPECT_THROW(simulation->set_variation(payload(-1.0, Eigen::Vector3d::Zero())),
               std::invalid_argument);
  EXPECT_FALSE(simulation->variation().has_payload());  // a refused variation changes nothing
}

INSTANTIATE_TEST_SUITE_P(Engines, PayloadEngine,
                         ::testing::Values(Backend{"Bullet", make_bullet},
                                           Backend{"MuJoCo", make_mujoco}),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace upkie_rl
