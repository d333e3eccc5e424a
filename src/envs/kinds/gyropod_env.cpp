#include "envs/kinds/gyropod_env.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include "envs/core/shared_options.hpp"

namespace upkie_rl {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kMaxPitchRate = 1000.0f;  // Observation bound of θ̇ [rad/s].

}  // namespace

GyropodEnv::GyropodEnv(std::unique_ptr<ServosEnv> servos, const GyropodConfig& config)
    : ServosWrapperEnv(std::move(servos), "GyropodEnv"),
      config_(config),
      commander_(servos_->model(), servos_->timestep(),
                 GroundVelocityCommanderConfig{config.leg_gain_scale}) {
  if (!(config_.max_ground_velocity > 0.0) || !(config_.max_yaw_velocity > 0.0)) {
    throw std::invalid_argument(
        "GyropodEnv: max_ground_velocity and max_yaw_velocity must be positive");
  }
  const auto v_max = static_cast<float>(config_.max_ground_velocity);
  const auto yaw_max = static_cast<float>(config_.max_yaw_velocity);
  const auto pi = std::numbers::pi_v<float>;
  observation_space_.add("p", -kInf, kInf);
  observation_space_.add("theta", -pi, pi);
  observation_space_.add("psi", -kInf, kInf);
  observation_space_.add("p_dot", -kInf, kInf);  // Measured: overshoots the command bound.
  observation_space_.add("theta_dot", -kMaxPitchRate, kMaxPitchRate);
  observation_space_.add("psi_dot", -yaw_max, yaw_max);
  action_space_.add("ground_velocity", -v_max, v_max);
  action_space_.add("yaw_velocity", -yaw_max, yaw_max);
}

void GyropodEnv::write_observation(const Observation& full, std::span<float> observation) const {
  if (observation.size() != 6) {
    throw std::invalid_argument("GyropodEnv: observation buffer has " +
                                std::to_string(observation.size()) + " components, expected 6");
  }
  observation[0] = static_cast<float>(full.wheel_odometry.position);
  observation[1] = static_cast<float>(full.base_orientation.pitch);
  observation[2] = static_cast<float>(yaw_);
  observation[3] = static_cast<float>(full.wheel_odometry.velocity);
  observation[4] = static_cast<float>(full.base_orientation.angular_velocity.y());
  observation[5] = static_cast<float>(yaw_velocity_);
}

void GyropodEnv::reset(std::optional<std::uint64_t> seed, std::span<float> observation) {
  const Observation& full = servos_->reset_servos(seed);
  commander_.reset(full);
  yaw_ = 0.0;
  yaw_velocity_ = 0.0;
  write_observation(full, observation);
}

StepResult GyropodEnv::step(std::span<const float> action, std::span<float> observation) {
  std::array<float, 2> command{};
  clamp_to_space(action_space_, action, command);
  const Observation& full = servos_->step_servos(commander_.command(command[0], command[1]));
  yaw_velocity_ = command[1];
  yaw_ += yaw_velocity_ * servos_->timestep();
  write_observation(full, observation);
  StepResult result;
  result.reward = 1.0;
  result.terminated = std::abs(full.base_orientation.pitch) > config_.fall_pitch;
  return result;
}

void GyropodConfig::declare_options(OptionTable& table) {
  table.add_real(kMaxGroundVelocityOption, &max_ground_velocity);
  table.add_real("max_yaw_velocity", &max_yaw_velocity, 1e-6, kOptionHuge,
                 "yaw velocity bound [rad/s]");
  table.add_real(kFallPitchOption, &fall_pitch);
  table.add_real(kLegGainScaleOption, &leg_gain_scale);
}

}  // namespace upkie_rl
