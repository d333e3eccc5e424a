#include "envs/init_randomization.hpp"

#include <Eigen/Geometry>

namespace upkie_rl {

ResetState InitRandomization::sample(std::mt19937_64& generator) const {
  ResetState state;
  const double roll_angle = uniform_symmetric(generator, roll);
  const double pitch_angle = uniform_symmetric(generator, pitch);
  state.orientation_base_in_world = Eigen::AngleAxisd(pitch_angle, Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(roll_angle, Eigen::Vector3d::UnitX());
  state.position_base_in_world.x() += uniform_symmetric(generator, x);
  state.position_base_in_world.z() += z * uniform_unit(generator);
  state.angular_velocity_base_in_base.x() = uniform_symmetric(generator, omega_x);
  state.angular_velocity_base_in_base.y() = uniform_symmetric(generator, omega_y);
  state.linear_velocity_base_to_world_in_world.x() = uniform_symmetric(generator, v_x);
  state.linear_velocity_base_to_world_in_world.y() = uniform_symmetric(generator, v_y);
  state.linear_velocity_base_to_world_in_world.z() = uniform_symmetric(generator, v_z);
  return state;
}

}  // namespace upkie_rl
