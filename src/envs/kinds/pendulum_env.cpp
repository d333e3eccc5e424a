#include "envs/kinds/pendulum_env.hpp"

#include <algorithm>
#include <numbers>
#include <stdexcept>
#include "envs/core/shared_options.hpp"

namespace upkie_rl {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kMaxPitchRate = 1000.0f;  // Observation bound of θ̇ [rad/s] (seed eq. 4).

}  // namespace

PendulumEnv::PendulumEnv(std::unique_ptr<ServosEnv> servos, const PendulumConfig& config)
    : ServosWrapperEnv(std::move(servos), "PendulumEnv"),
      config_(config),
      commander_(servos_->model(), servos_->timestep(),
                 GroundVelocityCommanderConfig{config.leg_gain_scale}),
      task_(config.reward, config.termination) {
  if (!(config_.max_ground_velocity > 0.0)) {
    throw std::invalid_argument("PendulumEnv: max_ground_velocity must be positive");
  }
  const auto a_max = static_cast<float>(config_.max_ground_velocity);
  const auto pi = std::numbers::pi_v<float>;
  observation_space_.add("theta", -pi, pi);
  observation_space_.add("p", -kInf, kInf);
  observation_space_.add("theta_dot", -kMaxPitchRate, kMaxPitchRate);
  // The seed bounds p_dot by +-a_max, but it is measured: the wheels overshoot the command
  // (episodes end only past 2 m/s). Unbounded, so that observations stay in the space as
  // Gymnasium and SB3 check; bounds enter neither the policy nor the normalisation.
  observation_space_.add("p_dot", -kInf, kInf);
  action_space_.add("ground_velocity", -a_max, a_max);
}

void PendulumEnv::write_observation(const Observation& full, std::span<float> observation) const {
  if (observation.size() != 4) {
    throw std::invalid_argument("PendulumEnv: observation buffer has " +
                                std::to_string(observation.size()) + " components, expected 4");
  }
  observation[0] = static_cast<float>(full.base_orientation.pitch);
  observation[1] = static_cast<float>(full.wheel_odometry.position);
  observation[2] = static_cast<float>(full.base_orientation.angular_velocity.y());
  observation[3] = static_cast<float>(full.wheel_odometry.velocity);
}

void PendulumEnv::reset(std::optional<std::uint64_t> seed, std::span<float> observation) {
  const Observation& full = servos_->reset_servos(seed);
  commander_.reset(full);
  task_.reset(full);
  write_observation(full, observation);
}

StepResult PendulumEnv::step(std::span<const float> action, std::span<float> observation) {
  float ground_velocity = 0.0f;
  clamp_to_space(action_space_, action, std::span<float>(&ground_velocity, 1));
  const Observation& full = servos_->step_servos(commander_.command(ground_velocity, 0.0));
  write_observation(full, observation);
  return task_.evaluate(full, ground_velocity);
}

void PendulumConfig::declare_options(OptionTable& table) {
  table.add_real(kMaxGroundVelocityOption, &max_ground_velocity);
  table.add_real(kLegGainScaleOption, &leg_gain_scale);
  termination.declare_options(table);
  reward.declare_options(table);
}

}  // namespace upkie_rl
