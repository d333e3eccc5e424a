#include "envs/randomization/observation_noise.hpp"

#include <cmath>

#include "sim/random_draws.hpp"

namespace upkie_rl {
namespace {

constexpr std::uint64_t kObservationNoiseStream = 2;

}  // namespace

ObservationNoise::ObservationNoise(std::unique_ptr<Env> env, double half_width)
    : EnvWrapper(std::move(env), "ObservationNoise"), half_width_(half_width) {
  if (!(std::isfinite(half_width) && half_width >= 0.0)) {
    throw std::invalid_argument("ObservationNoise: the half-width must be finite and >= 0");
  }
}

void ObservationNoise::add_noise(std::span<float> observation) {
  const double half_width = scale_ * half_width_;
  for (float& component : observation) {
    component += static_cast<float>(uniform_symmetric(generator_, half_width));
  }
}

void ObservationNoise::reset(std::optional<std::uint64_t> seed, std::span<float> observation) {
  if (seed) generator_.seed(derive_seed(*seed, kObservationNoiseStream));
  env_->reset(seed, observation);
  add_noise(observation);
}

StepResult ObservationNoise::step(std::span<const float> action, std::span<float> observation) {
  const StepResult result = env_->step(action, observation);
  add_noise(observation);
  return result;
}

void ObservationNoise::set_randomization_scale(double scale) {
  check_randomization_scale(scale);
  env_->set_randomization_scale(scale);
  scale_ = scale;
}

}  // namespace upkie_rl
