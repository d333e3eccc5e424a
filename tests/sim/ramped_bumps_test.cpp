/// Ramped bumps (FloorBumps::ramp, option bump_ramp), on Bullet and on MuJoCo: the surface
/// is the trapezoid's (flat top, a slope of ramp x height on each side), a tire resting on a
/// slope sits where the slope puts it, a ramp on bumps of height 0 changes nothing, and bad
/// ramps are refused by name.

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

/// Bumps of 4 cm every metre with a 3 cm top and 1:3 slopes (12 cm long): the bump at
/// x = 1 m rises from 0.865 m to 0.985 m and comes down from 1.015 m to 1.135 m.
FloorBumps ramped_bumps() {
  FloorBumps bumps;
  bumps.height = 0.04;
  bumps.spacing = 1.0;
  bumps.width = 0.03;
  bumps.ramp = 3.0;
  return bumps;
}

TEST(RampedBumps, SurfaceHeightIsTheTrapezoids) {
  const FloorBumps bumps = ramped_bumps();
  EXPECT_NEAR(bumps.ramp_run(), 0.12, 1e-12);
  EXPECT_NEAR(bumps.footprint(), 0.27, 1e-12);
  const struct {
    double x;
    double height;
  } profile[] = {
      {0.0, 0.0},    {0.5, 0.0},     {0.86, 0.0},  {0.865, 0.0},   {0.925, 0.02},
      {0.955, 0.03}, {0.985, 0.04},  {1.0, 0.04},  {1.015, 0.04},  {1.075, 0.02},
      {1.135, 0.0},  {-0.925, 0.02}, {20.0, 0.04}, {20.075, 0.02}, {21.0, 0.0},
  };
  for (const auto& [x, height] : profile) {
    EXPECT_NEAR(bumps.surface_height(x), height, 1e-12) << "x " << x;
  }
  FloorBumps square = bumps;
  square.ramp = 0.0;
  EXPECT_EQ(square.surface_height(0.984), 0.0);
  EXPECT_EQ(square.surface_height(0.986), 0.04);
}

/// Distance from `point` to the line through `a` and `b` in the (x, z) plane [m].
double distance_to_line(const std::array<double, 2>& point, const std::array<double, 2>& a,
                        const std::array<double, 2>& b) {
  const double dx = b[0] - a[0];
  const double dz = b[1] - a[1];
  return std::abs(dx * (point[1] - a[1]) - dz * (point[0] - a[0])) / std::hypot(dx, dz);
}

TEST(RampedBumps, AnInsetSectionHasEveryFaceMovedInByTheInset) {
  const FloorBumps bumps = ramped_bumps();
  const auto exact = bumps.ramped_section();
  const auto inset = bumps.ramped_section(0.001);
  // Top right, bottom right, bottom left, top left; the top 3 cm wide at 4 cm, the bottom
  // kBumpFooting below the floor, on the slopes' lines.
  EXPECT_NEAR(exact[0][0], 0.015, 1e-12);
  EXPECT_NEAR(exact[0][1], 0.04, 1e-12);
  EXPECT_NEAR(exact[1][0], 0.015 + 3.0 * (0.04 + kBumpFooting), 1e-12);
  EXPECT_NEAR(exact[1][1], -kBumpFooting, 1e-12);
  EXPECT_EQ(exact[3][0], -exact[0][0]);
  EXPECT_EQ(exact[2][0], -exact[1][0]);
  for (int corner = 0; corner < 4; ++corner) {
    const int next = (corner + 1) % 4;
    EXPECT_NEAR(distance_to_line(inset[corner], exact[corner], exact[next]), 0.001, 1e-12);
    EXPECT_NEAR(distance_to_line(inset[next], exact[corner], exact[next]), 0.001, 1e-12);
  }
}

struct Backend {
  const char* name;
  std::function<std::unique_ptr<PhysicsSimulation>(const PhysicsConfig&)> make;
};

class RampedBumpsOnEngine : public ::testing::TestWithParam<Backend> {
 protected:
  std::unique_ptr<PhysicsSimulation> make(const FloorBumps& bumps = {}) const {
    PhysicsConfig config;
    config.bumps = bumps;
    return GetParam().make(config);
  }
};

/// Where the lower tire's centre is once the robot, released at x = `x` with its legs
/// straight and held and its wheels still, has landed (0.15 s) [m].
Eigen::Vector3d landed_tire_centre(PhysicsSimulation& simulation, double x) {
  ResetState start;
  start.position_base_in_world.x() = x;
  simulation.reset(start);
  const double radius = simulation.model().wheel_radius();
  while (simulation.observation().time < 0.15) simulation.step(pendulum_action(0.0, radius));
  const testing::TireCentres tire_centres(simulation.model());
  const Eigen::Vector3d left = tire_centres(simulation.observation(), kLeftWheel);
  const Eigen::Vector3d right = tire_centres(simulation.observation(), kRightWheel);
  return left.z() < right.z() ? left : right;
}

TEST_P(RampedBumpsOnEngine, ATireOnASlopeRestsWhereTheSlopePutsIt) {
  const FloorBumps bumps = ramped_bumps();
  auto simulation = make(bumps);
  const double on_floor = landed_tire_centre(*simulation, 0.0).z();
  const double radius = simulation->model().wheel_radius();
  const double slope = std::atan(1.0 / bumps.ramp);
  // Up the slope of the bump at 1 m, down its far slope, and on the bump at -1 m. The tire
  // touches the slope r sin(slope) uphill of its centre, and its centre is r cos(slope)
  // above that point, against r on the floor. Measured: within 0.25 mm on both engines
  // (a hull not moved in by Bullet's margin would sit 1 mm higher).
  for (const double x : {0.88, 0.91, 0.94, 1.06, 1.09, 1.12, -0.91, -1.09}) {
    const Eigen::Vector3d centre = landed_tire_centre(*simulation, x);
    const double bump_centre = std::round(centre.x());
    const double uphill = centre.x() < bump_centre ? 1.0 : -1.0;
    const double touch_x = centre.x() + uphill * radius * std::sin(slope);
    const double expected = bumps.surface_height(touch_x) + radius * (std::cos(slope) - 1.0);
    ASSERT_GT(bumps.surface_height(touch_x), 0.002) << "x " << x;  // on the slope
    ASSERT_LT(bumps.surface_height(touch_x), 0.038) << "x " << x;
    EXPECT_NEAR(centre.z() - on_floor, expected, 5e-4) << "x " << x << ", tire at " << centre.x();
    EXPECT_TRUE(simulation->observation().floor_contact.contact) << "x " << x;
    EXPECT_FALSE(simulation->observation().floor_contact.non_wheel) << "x " << x;
  }
  // On the flat top, lifted by the full height.
  EXPECT_NEAR(landed_tire_centre(*simulation, 1.0).z() - on_floor, 0.04, 5e-4);
}

TEST_P(RampedBumpsOnEngine, ARampOnBumpsOfHeightZeroIsTheFlatFloorBitForBit) {
  FloorBumps none = ramped_bumps();
  none.height = 0.0;
  none.ramp = 10.0;
  auto nominal = make();
  auto ramp_only = make(none);
  const std::vector<Eigen::Vector3d> expected = balance_trajectory(*nominal);
  const std::vector<Eigen::Vector3d> actual = balance_trajectory(*ramp_only);
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t step = 0; step < expected.size(); ++step) {
    ASSERT_EQ(actual[step], expected[step]) << "step " << step;
  }
  EXPECT_GT((expected.front() - expected.back()).norm(), 0.01);  // the robot moved
}

/// The message of the std::invalid_argument making a simulation with `bumps` throws, or ""
/// if it does not throw.
std::string refusal(const Backend& backend, const FloorBumps& bumps) {
  PhysicsConfig config;
  config.bumps = bumps;
  try {
    backend.make(config);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST_P(RampedBumpsOnEngine, BadRampsAreRefusedByName) {
  const auto with_ramp = [](double ramp, double spacing = 1.0) {
    FloorBumps bumps = ramped_bumps();
    bumps.ramp = ramp;
    bumps.spacing = spacing;
    return bumps;
  };
  for (const double ramp : {-0.5, 10.5, std::numeric_limits<double>::quiet_NaN()}) {
    const std::string message = refusal(GetParam(), with_ramp(ramp));
    EXPECT_NE(message.find("bump_ramp"), std::string::npos) << "\"" << message << "\"";
  }
  // Footprint 0.03 + 2 x 5 x 0.04 = 0.43 m, more than half of 0.8 m: slopes nearly
  // touching. The same top without slopes fits.
  const std::string message = refusal(GetParam(), with_ramp(5.0, 0.8));
  for (const char* named : {"bump_ramp", "bump_width", "bump_height", "bump_spacing"}) {
    EXPECT_NE(message.find(named), std::string::npos) << "\"" << message << "\"";
  }
  EXPECT_EQ(refusal(GetParam(), with_ramp(0.0, 0.8)), "");
  EXPECT_EQ(refusal(GetParam(), with_ramp(4.0, 0.8)), "");  // 0.35 m
}

INSTANTIATE_TEST_SUITE_P(Engines, RampedBumpsOnEngine,
                         ::testing::Values(Backend{"Bullet", make_bullet},
                                           Backend{"MuJoCo", make_mujoco}),
                         [](const ::testing::TestParamInfo<Backend>& info) {
                           return std::string(info.param.name);
                         });

TEST(MujocoRampedBumps, AMeshGeomPerBumpWhoseCornersAreTheSections) {
  const auto robot = RobotModel::default_model();
  MujocoConfig config;
  config.bumps = ramped_bumps();
  const auto compiled = build_mujoco_model(*robot, config);
  const mjModel* m = compiled->model.get();
  mjData* d = mj_makeData(m);
  mj_kinematics(m, d);
  const MujocoRobotIndex& index = compiled->index;
  ASSERT_EQ(index.num_bump_geoms, 40);
  const auto section = config.bumps.ramped_section();
  for (int bump = 0; bump < index.num_bump_geoms; ++bump) {
    const int geom = index.first_bump_geom + bump;
    EXPECT_TRUE(index.is_ground(geom));
    ASSERT_EQ(m->geom_type[geom], mjGEOM_MESH);
    EXPECT_EQ(m->geom_friction[3 * geom], m->geom_friction[3 * index.floor_geom]);
    const int mesh = m->geom_dataid[geom];
    ASSERT_EQ(m->mesh_vertnum[mesh], 8);
    // Every vertex, in the world, is a corner of the section at y = ±20 m around the
    // bump's centre (MuJoCo moves a mesh to its centre of mass and the geom with it).
    const double centre = bump < 20 ? bump - 20 : bump - 19;
    for (int vertex = 0; vertex < 8; ++vertex) {
      const float* local = m->mesh_vert + 3 * (m->mesh_vertadr[mesh] + vertex);
      Eigen::Vector3d world = Eigen::Map<const Eigen::Vector3d>(d->geom_xpos + 3 * geom);
      for (int row = 0; row < 3; ++row) {
        for (int col = 0; col < 3; ++col)
          world[row] += d->geom_xmat[9 * geom + 3 * row + col] * local[col];
      }
      double nearest = std::numeric_limits<double>::infinity();
      for (const auto& [x, z] : section) {
        nearest = std::min(nearest, std::hypot(world.x() - centre - x, world.z() - z));
      }
      EXPECT_LT(nearest, 1e-6) << "bump " << bump << " vertex " << vertex;
      EXPECT_NEAR(std::abs(world.y()), kBumpLength / 2.0, 1e-5);
    }
  }
  mj_deleteData(d);
}

}  // namespace
}  // namespace upkie_rl
