#pragma once
/// @file
/// ServosWrapperEnv: the common base of the environments built on a ServosEnv (pendulum,
/// gyropod, servos task): it owns the servos environment and the two spaces, and passes
/// the full observation and timing through.

#include <memory>
#include <stdexcept>
#include <string>

#include "envs/core/env.hpp"
#include "envs/kinds/servos_env.hpp"

namespace upkie_rl {

/// An environment whose observations and actions are a view of a ServosEnv's.
class ServosWrapperEnv : public Env {
 public:
  ServosEnv& servos() { return *servos_; }
  const ServosEnv& servos() const { return *servos_; }

  const BoxSpace& observation_space() const override { return observation_space_; }
  const BoxSpace& action_space() const override { return action_space_; }
  const Observation* full_observation() const override { return servos_->full_observation(); }
  void set_randomization_scale(double scale) override { servos_->set_randomization_scale(scale); }
  double timestep() const override { return servos_->timestep(); }
  int physics_steps_per_step() const override { return servos_->physics_steps_per_step(); }

 protected:
  /// @throws std::invalid_argument, naming `env_name`, when `servos` is null.
  ServosWrapperEnv(std::unique_ptr<ServosEnv> servos, const std::string& env_name)
      : servos_(std::move(servos)) {
    if (!servos_) throw std::invalid_argument(env_name + ": null servos environment");
  }

  std::unique_ptr<ServosEnv> servos_;
  BoxSpace observation_space_;
  BoxSpace action_space_;
};

}  // namespace upkie_rl
