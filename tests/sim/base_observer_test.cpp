#include "sim/base_observer.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <numbers>

namespace upkie_rl {
namespace {

Eigen::Matrix3d rotation(double yaw, double pitch) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()))
      .toRotationMatrix();
}

TEST(BaseYaw, IsTheHeadingOfTheBaseXAxis) {
  EXPECT_DOUBLE_EQ(base_yaw(Eigen::Matrix3d::Identity()), 0.0);
  EXPECT_NEAR(base_yaw(rotation(0.7, 0.0)), 0.7, 1e-12);
  EXPECT_NEAR(base_yaw(rotation(-2.5, 0.0)), -2.5, 1e-12);
  EXPECT_NEAR(std::abs(base_yaw(rotation(std::numbers::pi, 0.0))), std::numbers::pi, 1e-12);
}

TEST(BaseYaw, DoesNotDependOnThePitch) {
  for (double pitch : {-1.0, -0.3, 0.2, 1.2}) {
    EXPECT_NEAR(base_yaw(rotation(1.1, pitch)), 1.1, 1e-12) << pitch;
    EXPECT_NEAR(base_pitch(Eigen::Quaterniond(rotation(1.1, pitch))), pitch, 1e-12) << pitch;
  }
}

}  // namespace
}  // namespace upkie_rl
