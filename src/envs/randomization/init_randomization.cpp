#include "envs/randomization/init_randomization.hpp"

#include <Eigen/Geometry>
#include "envs/core/shared_options.hpp"

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

void InitRandomization::declare_options(OptionTable& table) {
  table.add_real("init_rand_roll", &roll, 0.0, 3.2, "initial roll drawn in +-it [rad]");
  table.add_real("init_rand_pitch", &pitch, 0.0, 3.2, "initial pitch drawn in +-it [rad]");
  table.add_real("init_rand_x", &x, 0.0, kOptionHuge, "initial x drawn in +-it [m]");
  table.add_real("init_rand_z", &z, 0.0, kOptionHuge, "initial height raised by [0, it] [m]");
  table.add_real("init_rand_omega_x", &omega_x, 0.0, kOptionHuge,
                 "initial roll rate drawn in +-it [rad/s]");
  table.add_real("init_rand_omega_y", &omega_y, 0.0, kOptionHuge,
                 "initial pitch rate drawn in +-it [rad/s]");
  table.add_real("init_rand_v_x", &v_x, 0.0, kOptionHuge, "initial x velocity in +-it [m/s]");
  table.add_real("init_rand_v_y", &v_y, 0.0, kOptionHuge, "initial y velocity in +-it [m/s]");
  table.add_real("init_rand_v_z", &v_z, 0.0, kOptionHuge, "initial z velocity in +-it [m/s]");
}

}  // namespace upkie_rl
