/// Bumps across the floor (PhysicsConfig::bumps), on Bullet and on MuJoCo: a tire on a bump
/// is lifted by its height, ahead of and behind the start, up to the field's end; without
/// bumps nothing changes, bit for bit; an episode's variation can leave them out; bad
/// settings are refused by name.

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "sim/balance_trajectory.hpp"
#include "sim/floor_bumps.hpp"
#include "sim/mujoco_model.hpp"
#include "sim/physics_backends.hpp"
#include "sim/servo_actions.hpp"
#include "sim/tire_centres.hpp"

namespace upkie_rl {
namespace {

using testing::balance_trajectory;
using testing::make_bullet;
using testing::make_mujoco;
using testing::pendulum_action;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Bumps of 2 cm, 3 cm wide, every metre: the nearest at x = ±1 m, the last at ±20 m.
FloorBumps two_centimetre_bumps() {
  FloorBumps bumps;
  bumps.height = 0.02;
  bumps.spacing = 1.0;
  bumps.width = 0.03;
  return bumps;
}

TEST(FloorBumps, CentresEverySpacingOnBothSidesUpToTheFieldsEnd) {
  FloorBumps bumps = two_centimetre_bumps();
  const std::vector<double> centres = bumps.centres();
  ASSERT_EQ(centres.size(), 40u);
  EXPECT_EQ(centres.front(), -20.0);
  EXPECT_EQ(centres[19], -1.0);
  EXPECT_EQ(centres[20], 1.0);
  EXPECT_EQ(centres.back(), 20.0);
  bumps.spacing = 0.3;  // 66 × 0.3 = 19.8 m
  EXPECT_EQ(bumps.centres().size(), 132u);
  EXPECT_NEAR(bumps.centres().back(), 19.8, 1e-12);
  bumps.height = 0.0;
  EXPECT_TRUE(bumps.centres().empty());
}

struct Backend {
  const char* name;
  std::function<std::unique_ptr<PhysicsSimulation>(const PhysicsConfig&)> make;
};

class FloorBumpsOnEngine : public ::testing::TestWithParam<Backend> {
 protected:
  std::unique_ptr<PhysicsSimulation> make(const FloorBumps& bumps = {}) const {
    PhysicsConfig config;
    config.bumps = bumps;
    return GetParam().make(config);
  }
};

/// Height of the lower tire's centre once the robot, released at x = `x` with its legs
/// held and its wheels still, has landed (0.15 s) [m]; `contact` is its floor contact.
double landed_tire_height(PhysicsSimulation& simulation, double x, bool& contact) {
  ResetState start;
  start.position_base_in_world.x() = x;
  simulation.reset(start);
  const double radius = simulation.model().wheel_radius();
  while (simulation.observation().time < 0.15) simulation.step(pendulum_action(0.0, radius));
  const testing::TireCentres tire_centres(simulation.model());
  const Observation& observation = simulation.observation();
  contact = observation.floor_contact.contact;
  return std::min(tire_centres(observation, kLeftWheel).z(),
                  tire_centres(observation, kRightWheel).z());
}

TEST_P(FloorBumpsOnEngine, ATireOnABumpIsLiftedByItsHeight) {
  auto bumpy = make(two_centimetre_bumps());
  auto flat = make();
  bool contact = false;
  const double on_floor = landed_tire_height(*bumpy, 0.0, contact);
  EXPECT_TRUE(contact);
  // Measured: 20.1 mm on Bullet, 20.2 mm on MuJoCo (the soft tires sink by about 1 mm on
  // the floor and on a bump alike).
  for (const double x : {1.0, -1.0, 5.0, 20.0, -20.0}) {
    EXPECT_NEAR(landed_tire_height(*bumpy, x, contact) - on_floor, 0.02, 1e-3) << "x " << x;
    EXPECT_TRUE(contact) << "x " << x;  // a bump is floor
    EXPECT_NEAR(landed_tire_height(*flat, x, contact) - on_floor, 0.0, 1e-4) << "x " << x;
  }
  // Between bumps and past the field's end, the floor.
  for (const double x : {0.5, -2.5, 21.0}) {
    EXPECT_NEAR(landed_tire_height(*bumpy, x, contact) - on_floor, 0.0, 1e-4) << "x " << x;
  }
}

TEST_P(FloorBumpsOnEngine, AnEpisodeWithoutTheBumpsHasAFlatFloorAndTheNextHasThemAgain) {
  auto bumpy = make(two_centimetre_bumps());
  bool contact = false;
  const double on_floor = landed_tire_height(*bumpy, 0.0, contact);
  PhysicsVariation without_bumps;
  without_bumps.floor_bumps = false;
  bumpy->set_variation(without_bumps);
  for (const double x : {1.0, -1.0, 20.0}) {
    EXPECT_NEAR(landed_tire_height(*bumpy, x, contact) - on_floor, 0.0, 1e-4) << "x " << x;
    EXPECT_TRUE(contact) << "x " << x;
  }
  bumpy->set_variation(PhysicsVariation{});
  EXPECT_NEAR(landed_tire_height(*bumpy, 1.0, contact) - on_floor, 0.02, 1e-3);
}

TEST_P(FloorBumpsOnEngine, HeightZeroIsTheFlatFloorBitForBit) {
  FloorBumps none;
  none.spacing = 0.2;  // any spacing and width: height 0 adds nothing
  none.width = 0.1;
  auto nominal = make();
  auto zero_height = make(none);
  const std::vector<Eigen::Vector3d> expected = balance_trajectory(*nominal);
  const std::vector<Eigen::Vector3d> actual = balance_trajectory(*zero_height);
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t step = 0; step < expected.size(); ++step) {
    ASSERT_EQ(actual[step], expected[step]) << "step " << step;
  }
  EXPECT_GT((expected.front() - expected.back()).norm(), 0.01);  // the robot moved
}

/// The message of the std::invalid_argument making a simulation with `bumps` (and
/// `floor`) throws, or "" if it does not throw.
std::string refusal(const Backend& backend, const FloorBumps& bumps, bool floor = true) {
  PhysicsConfig config;
  config.bumps = bumps;
  config.floor = floor;
  try {
    backend.make(config);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST_P(FloorBumpsOnEngine, BadSettingsAreRefusedByName) {
  const auto with = [](auto change) {
    FloorBumps bumps = two_centimetre_bumps();
    change(bumps);
    return bumps;
  };
  const struct {
    FloorBumps bumps;
    const char* named;
  } cases[] = {
      {with([](FloorBumps& b) { b.height = 0.06; }), "bump_height"},
      {with([](FloorBumps& b) { b.height = -0.01; }), "bump_height"},
      {with([](FloorBumps& b) { b.height = kNaN; }), "bump_height"},
      {with([](FloorBumps& b) { b.spacing = 0.1; }), "bump_spacing"},
      {with([](FloorBumps& b) { b.spacing = 11.0; }), "bump_spacing"},
      {with([](FloorBumps& b) { b.width = 0.001; }), "bump_width"},
      {with([](FloorBumps& b) { b.width = 0.6; }), "bump_width"},
      // Wider than half the spacing: no room between bumps.
      {with([](FloorBumps& b) {
         b.spacing = 0.5;
         b.width = 0.3;
       }),
       "bump_width"},
  };
  for (const auto& [bumps, named] : cases) {
    const std::string message = refusal(GetParam(), bumps);
    EXPECT_NE(message.find(named), std::string::npos) << "\"" << message << "\"";
  }
  const std::string message = refusal(GetParam(), two_centimetre_bumps(), /*floor=*/false);
  EXPECT_NE(message.find("bump_height needs the floor"), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(Engines, FloorBumpsOnEngine,
                         ::testing::Values(Backend{"Bullet", make_bullet},
                                           Backend{"MuJoCo", make_mujoco}),
                         [](const ::testing::TestParamInfo<Backend>& info) {
                           return std::string(info.param.name);
                         });

TEST(MujocoFloorBumps, ABoxGeomPerBumpTouchedAsTheFloor) {
  const auto robot = RobotModel::default_model();
  const auto flat = build_mujoco_model(*robot, MujocoConfig{});
  MujocoConfig config;
  config.bumps = two_centimetre_bumps();
  const auto bumpy = build_mujoco_model(*robot, config);
  const mjModel* m = bumpy->model.get();
  const MujocoRobotIndex& index = bumpy->index;
  EXPECT_EQ(flat->index.num_bump_geoms, 0);
  ASSERT_EQ(index.num_bump_geoms, 40);
  EXPECT_EQ(m->ngeom, flat->model->ngeom + 40);
  const int floor = index.floor_geom;
  for (int bump = 0; bump < index.num_bump_geoms; ++bump) {
    const int geom = index.first_bump_geom + bump;
    EXPECT_TRUE(index.is_ground(geom));
    EXPECT_EQ(m->geom_type[geom], mjGEOM_BOX);
    EXPECT_EQ(m->geom_bodyid[geom], 0);  // the world's
    EXPECT_EQ(m->geom_contype[geom], m->geom_contype[floor]);
    EXPECT_EQ(m->geom_conaffinity[geom], m->geom_conaffinity[floor]);
    EXPECT_EQ(m->geom_friction[3 * geom], m->geom_friction[3 * floor]);
    // Top at 2 cm, 3 cm along x, centred on x = ±1, ±2, ... m.
    EXPECT_NEAR(m->geom_pos[3 * geom + 2] + m->geom_size[3 * geom + 2], 0.02, 1e-12);
    EXPECT_NEAR(m->geom_size[3 * geom], 0.015, 1e-12);
    EXPECT_NEAR(m->geom_pos[3 * geom], bump < 20 ? bump - 20 : bump - 19, 1e-12);
  }
  for (const int tire : index.tire_geoms) EXPECT_FALSE(index.is_ground(tire));
  EXPECT_TRUE(index.is_ground(floor));
}

}  // namespace
}  // namespace upkie_rl
