#pragma once
/// @file
/// ObservationNoise: uniform noise on every observation component (ppo_balancer's
/// sim-to-real wrapper).

#include <random>

#include "envs/wrappers/env_wrapper.hpp"

namespace upkie_rl {

/// Adds U(-half_width, half_width) to each component of the observations it returns (the
/// reward and terminations of the inner environment still see the true state). Its
/// generator is re-seeded from each reset's seed, on its own stream.
class ObservationNoise final : public EnvWrapper {
 public:
  /// @throws std::invalid_argument on a null env or a negative or non-finite half-width.
  ObservationNoise(std::unique_ptr<Env> env, double half_width);

  void reset(std::optional<std::uint64_t> seed, std::span<float> observation) override;
  StepResult step(std::span<const float> action, std::span<float> observation) override;
  void set_randomization_scale(double scale) override;

 private:
  void add_noise(std::span<float> observation);

  double half_width_;
  double scale_ = 1.0;
  std::mt19937_64 generator_{0};
};

}  // namespace upkie_rl
