#include "envs/init_randomization.hpp"

#include <Eigen/Geometry>

namespace upkie_rl {

namespace {

/// Uniform draw in [-half_width, half_width].
double symmetric(std::mt19937_64& generator, double half_width) {
  return half_width * (2.0 * uniform_unit(generator) - 1.0);
}

}  // namespace

ResetState InitRandomization::sample(std::mt19937_64& generator) const {
  ResetState state;
  const double roll_angle = symmetric(generator, roll);
  const double pitch_angle = symmetric(generator, pitch);
  state.orientation_base_in_world = Eigen::AngleAxisd(pitch_angle, Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(roll_angle, Eigen::Vector3d::UnitX());
  state.position_base_in_world.x() += symmetric(generator, x);
  state.position_base_in_world.z() += z * uniform_unit(generator);
  state.angular_velocity_base_in_base.x() = symmetric(generator, omega_x);
  state.angular_velocity_base_in_base.y() = symmetric(generator, omega_y);
  state.linear_velocity_base_to_world_in_world.x() = symmetric(generator, v_x);
  state.linear_velocity_base_to_world_in_world.y() = symmetric(generator, v_y);
  state.linear_velocity_base_to_world_in_world.z() = symmetric(generator, v_z);
  return state;
}

}  // namespace upkie_rl
