#include "cli/spine_world.hpp"

#include <random>
#include <stdexcept>

#include "base/option_table.hpp"

namespace upkie_rl::apps {

SpineWorld::SpineWorld(const std::vector<std::string>& physics_options)
    : options_(parse_env_options(physics_options)) {
  OptionTable table;
  perturbations_.declare_options(table);
  table.apply(options_, "--physics-option");
  if (perturbations_.push.enabled()) {
    throw std::invalid_argument(
        "--physics-option push_force: the spine pushes with --push-force, --push-time and "
        "--push-duration");
  }
}

PhysicsVariation SpineWorld::episode_variation(std::uint64_t start,
                                               const ImuUncertainty& start_imu) const {
  PhysicsVariation variation;  // the nominal robot, bit for bit, without options
  if (any()) {
    std::mt19937_64 generator(start);
    variation = perturbations_.sample(generator, 1.0);
  }
  if (!start_imu.is_zero()) variation.imu = start_imu;
  variation.noise_seed = start;  // each episode its own, reproducible, noise
  return variation;
}

}  // namespace upkie_rl::apps
