#pragma once
/// @file
/// SpineWorld: the physics a simulation spine plays besides the nominal robot
/// (`upkie-rl spine --physics-option NAME=VALUE`), hidden from the agents it serves.
///
/// Why: to play "reality" for an agent (the sim2real demo, a runner's rehearsal), the
/// spine must differ from the agent's simulation the way a robot does (payload, floor,
/// motors, IMU) without the agent being told. The names and ranges are the environments'
/// perturbation options, so a world written for `rollout --env-option` or fitted by
/// `upkie-rl identify` is given to the spine as it is.

#include <cstdint>
#include <string>
#include <vector>

#include "envs/core/env_options.hpp"
#include "envs/randomization/perturbation_settings.hpp"
#include "sim/imu_uncertainty.hpp"
#include "sim/physics_variation.hpp"

namespace upkie_rl::apps {

/// The perturbation options of a spine; a randomisation range draws again at each Start.
class SpineWorld {
 public:
  /// @param physics_options "NAME=VALUE" strings: the environments' perturbation options.
  /// @throws std::invalid_argument naming a malformed or unknown option, a value out of its
  ///         range, or pushes (the spine's are --push-force, --push-time, --push-duration).
  explicit SpineWorld(const std::vector<std::string>& physics_options);

  /// Whether any option differs from the nominal robot and world.
  bool any() const { return perturbations_.any(); }

  /// The variation of the episode of the `start`-th Start (0 first), reproducible from it;
  /// the IMU's biases and noise are the Start configuration's when it sets any
  /// (`start_imu`, as the robot's agents configure them), else the world's.
  PhysicsVariation episode_variation(std::uint64_t start, const ImuUncertainty& start_imu) const;

  /// The options as given ("mass_scale=1.2 payload_mass=1"), for the log.
  std::string describe() const { return format_env_options(options_); }

 private:
  EnvOptions options_;
  PerturbationSettings perturbations_;
};

}  // namespace upkie_rl::apps
