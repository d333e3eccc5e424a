#include "sim/floor_slope.hpp"

#include <Eigen/Geometry>

namespace upkie_rl {

FloorSlope make_floor_slope(double pitch, double roll, double heading, double gravity) {
  FloorSlope slope;
  const Eigen::Vector3d level_gravity(0.0, 0.0, -gravity);
  // A flat floor skips the products: the nominal world keeps its gravity to the last bit.
  if (pitch == 0.0 && roll == 0.0) {
    slope.gravity_in_floor = level_gravity;
    return slope;
  }
  const Eigen::Matrix3d heading_rotation =
      Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d tilt = (Eigen::AngleAxisd(-pitch, Eigen::Vector3d::UnitY()) *
                                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                                   .toRotationMatrix();
  slope.rotation_floor_to_level = heading_rotation * tilt * heading_rotation.transpose();
  slope.gravity_in_floor = slope.rotation_floor_to_level.transpose() * level_gravity;
  slope.tilted = true;
  return slope;
}

}  // namespace upkie_rl
