#pragma once
/// @file
/// EnvWrapper: an environment that wraps another and passes everything through unless it
/// overrides it (Gymnasium's Wrapper).

#include <memory>
#include <stdexcept>
#include <string>

#include "envs/core/env.hpp"

namespace upkie_rl {

/// Forwards every call to the wrapped environment.
class EnvWrapper : public Env {
 public:
  Env& inner() { return *env_; }
  const Env& inner() const { return *env_; }

  const BoxSpace& observation_space() const override { return env_->observation_space(); }
  const BoxSpace& action_space() const override { return env_->action_space(); }
  void reset(std::optional<std::uint64_t> seed, std::span<float> observation) override {
    env_->reset(seed, observation);
  }
  StepResult step(std::span<const float> action, std::span<float> observation) override {
    return env_->step(action, observation);
  }
  const Observation* full_observation() const override { return env_->full_observation(); }
  void neutral_action(std::span<float> action) const override { env_->neutral_action(action); }
  void set_randomization_scale(double scale) override { env_->set_randomization_scale(scale); }
  std::span<const std::string_view> reward_term_names() const override {
    return env_->reward_term_names();
  }
  std::span<const double> reward_terms() const override { return env_->reward_terms(); }
  const MirrorSymmetry* mirror_symmetry() const override { return env_->mirror_symmetry(); }
  double timestep() const override { return env_->timestep(); }
  int physics_steps_per_step() const override { return env_->physics_steps_per_step(); }

 protected:
  /// @throws std::invalid_argument, naming `wrapper_name`, when `env` is null.
  EnvWrapper(std::unique_ptr<Env> env, const std::string& wrapper_name) : env_(std::move(env)) {
    if (!env_) throw std::invalid_argument(wrapper_name + ": null environment");
  }

  std::unique_ptr<Env> env_;
};

}  // namespace upkie_rl
