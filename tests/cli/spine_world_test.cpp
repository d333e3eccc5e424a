#include "cli/spine_world.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>
#include "common/error_message.hpp"

namespace upkie_rl::apps {
namespace {

/// The message of the std::invalid_argument SpineWorld throws for `options`, "" if none.
std::string refusal(const std::vector<std::string>& options) {
  return testing::error_message([&] { SpineWorld world(options); });
}

TEST(SpineWorld, WithoutOptionsEveryEpisodeIsTheNominalRobot) {
  const SpineWorld world({});
  EXPECT_FALSE(world.any());
  const PhysicsVariation variation = world.episode_variation(3, {});
  EXPECT_FALSE(variation.changes_model());
  EXPECT_FALSE(variation.has_payload());
  EXPECT_EQ(variation.noise_seed, 3u);
}

TEST(SpineWorld, FixedOptionsGiveTheSameWorldInEveryEpisode) {
  const SpineWorld world({"payload_mass=1", "payload_offset_x=0.04", "floor_friction=0.6"});
  EXPECT_TRUE(world.any());
  for (std::uint64_t start = 0; start < 3; ++start) {
    const PhysicsVariation variation = world.episode_variation(start, {});
    EXPECT_EQ(variation.payload_mass, 1.0);
    EXPECT_EQ(variation.payload_offset.x(), 0.04);
    EXPECT_EQ(variation.floor_friction_scale, 0.6);
  }
  EXPECT_EQ(world.describe(), "payload_mass=1 payload_offset_x=0.04 floor_friction=0.6");
}

TEST(SpineWorld, RangesDrawAgainAtEachStartReproducibly) {
  const SpineWorld world({"payload_mass_variation=1"});
  const double first = world.episode_variation(0, {}).payload_mass;
  EXPECT_EQ(world.episode_variation(0, {}).payload_mass, first);
  EXPECT_NE(world.episode_variation(1, {}).payload_mass, first);
}

TEST(SpineWorld, TheStartConfigurationsImuWinsWhenItSetsOne) {
  const SpineWorld world({"imu_gyroscope_bias_fixed_y=0.03"});
  EXPECT_EQ(world.episode_variation(0, {}).imu.gyroscope_bias.y(), 0.03);
  ImuUncertainty start_imu;
  start_imu.gyroscope_noise = 0.01;
  const PhysicsVariation variation = world.episode_variation(0, start_imu);
  EXPECT_EQ(variation.imu.gyroscope_bias.y(), 0.0);
  EXPECT_EQ(variation.imu.gyroscope_noise, 0.01);
}

TEST(SpineWorld, BadOptionsAreRefusedNamingThem) {
  EXPECT_NE(refusal({"payload_mas=1"}).find("payload_mas"), std::string::npos);
  EXPECT_NE(refusal({"payload_mass=9"}).find("payload_mass"), std::string::npos);
  EXPECT_NE(refusal({"floor_friction"}).find("floor_friction"), std::string::npos);
  EXPECT_NE(refusal({"push_force=20"}).find("--push-force"), std::string::npos);
  EXPECT_EQ(refusal({"push_interval=2"}), "");  // no push without a force
}

}  // namespace
}  // namespace upkie_rl::apps
