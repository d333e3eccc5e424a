#include "envs/randomization/perturbation_settings.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "envs/core/shared_options.hpp"
#include "model/joint_order.hpp"
#include "sim/random_draws.hpp"

namespace upkie_rl {
namespace {

/// Stream of the randomised slopes, payloads and motor weakness (derive_seed).
constexpr std::uint64_t kRandomizedWorldStream = 11;

}  // namespace

bool PerturbationSettings::any() const {
  return mass_scale != 1.0 || inertia_variation != 0.0 || joint_friction != 0.0 ||
         joint_friction_fixed != 0.0 || wheel_servo_gain_scale != 1.0 ||
         leg_servo_gain_scale != 1.0 || !imu_gyroscope_bias_fixed.isZero(0.0) ||
         torque_control_noise != 0.0 || torque_measurement_noise != 0.0 ||
         imu_accelerometer_bias != 0.0 || imu_accelerometer_noise != 0.0 ||
         imu_gyroscope_bias != 0.0 || imu_gyroscope_noise != 0.0 || floor_friction != 1.0 ||
         floor_friction_variation != 0.0 || slope_pitch != 0.0 || slope_roll != 0.0 ||
         payload_mass != 0.0 || torque_limit_scale != 1.0 || slope_variation != 0.0 ||
         payload_mass_variation != 0.0 || payload_offset_variation != 0.0 ||
         torque_limit_variation != 0.0 || bump_share != 1.0 || push.enabled();
}

PhysicsVariation PerturbationSettings::sample(std::mt19937_64& generator, double scale) const {
  PhysicsVariation variation;
  for (double& body_scale : variation.mass_scale) {
    body_scale = mass_scale * (1.0 + uniform_symmetric(generator, scale * inertia_variation));
  }
  for (double& friction : variation.joint_friction) {
    friction = scale * joint_friction * uniform_unit(generator) + joint_friction_fixed;
  }
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    variation.servo_gain_scale[servo] =
        is_wheel(servo) ? wheel_servo_gain_scale : leg_servo_gain_scale;
  }
  variation.torque_control_noise = scale * torque_control_noise;
  variation.torque_measurement_noise = scale * torque_measurement_noise;
  ImuUncertainty& imu = variation.imu;
  for (int i = 0; i < 3; ++i) {
    imu.accelerometer_bias[i] = uniform_symmetric(generator, scale * imu_accelerometer_bias);
    imu.gyroscope_bias[i] =
        uniform_symmetric(generator, scale * imu_gyroscope_bias) + imu_gyroscope_bias_fixed[i];
  }
  imu.accelerometer_noise = scale * imu_accelerometer_noise;
  imu.gyroscope_noise = scale * imu_gyroscope_noise;
  variation.floor_friction_scale =
      floor_friction * (1.0 + uniform_symmetric(generator, scale * floor_friction_variation));
  variation.torque_limit_scale = torque_limit_scale;  // fixed: no draw
  // Fixed values: no draws, so that a seed gives the same draws with or without them.
  variation.slope_pitch = degrees_to_radians(slope_pitch);
  variation.slope_roll = degrees_to_radians(slope_roll);
  variation.payload_mass = payload_mass;
  variation.payload_offset = Eigen::Vector3d(payload_offset_x, payload_offset_y, payload_offset_z);
  variation.noise_seed = generator();
  add_randomized_world(variation, scale);
  return variation;
}

void PerturbationSettings::add_randomized_world(PhysicsVariation& variation, double scale) const {
  // A stream of its own, derived from the episode's noise seed: the draws above (and so
  // every trajectory without these options) are the same with or without them.
  std::mt19937_64 generator(derive_seed(variation.noise_seed, kRandomizedWorldStream));
  variation.slope_pitch +=
      degrees_to_radians(uniform_symmetric(generator, scale * slope_variation));
  variation.slope_roll += degrees_to_radians(uniform_symmetric(generator, scale * slope_variation));
  variation.payload_mass += scale * payload_mass_variation * uniform_unit(generator);
  variation.payload_offset.x() += uniform_symmetric(generator, scale * payload_offset_variation);
  variation.payload_offset.y() += uniform_symmetric(generator, scale * payload_offset_variation);
  variation.torque_limit_scale *= 1.0 - scale * torque_limit_variation * uniform_unit(generator);
  // Drawn last, so that the draws above are the same with or without it.
  variation.floor_bumps = uniform_unit(generator) < bump_share;
  // Clamped to the domains PhysicsVariation::validate checks (a fixed value plus its
  // variation may reach past them).
  const double max_slope = degrees_to_radians(kMaxSlopeDegrees);
  variation.slope_pitch = std::clamp(variation.slope_pitch, -max_slope, max_slope);
  variation.slope_roll = std::clamp(variation.slope_roll, -max_slope, max_slope);
  variation.payload_mass = std::min(variation.payload_mass, kMaxPayloadMass);
  for (int axis = 0; axis < 2; ++axis) {
    variation.payload_offset[axis] =
        std::clamp(variation.payload_offset[axis], -kMaxPayloadOffset, kMaxPayloadOffset);
  }
}

void PerturbationSettings::declare_options(OptionTable& table) {
  table.add_real("mass_scale", &mass_scale, 0.01, 100.0, "factor on every body's mass and inertia");
  table.add_real("inertia_variation", &inertia_variation, 0.0, 0.99,
                 "each body's mass and inertia times 1 + U(-it, it), drawn at reset");
  table.add_real("joint_friction", &joint_friction, 0.0, kOptionHuge,
                 "each joint's kinetic friction drawn in U(0, it) at reset [N.m]");
  table.add_real("joint_friction_fixed", &joint_friction_fixed, 0.0, 10.0,
                 "fixed kinetic friction of every joint, added to the drawn one [N.m]");
  table.add_real("wheel_servo_gain_scale", &wheel_servo_gain_scale, 0.1, 10.0,
                 "factor on the wheel servos' kp and kd (the real servos' gains)");
  table.add_real("leg_servo_gain_scale", &leg_servo_gain_scale, 0.1, 10.0,
                 "factor on the hip and knee servos' kp and kd");
  table.add_real("torque_control_noise", &torque_control_noise, 0.0, kOptionHuge,
                 "std of Gaussian noise on applied joint torques [N.m]");
  table.add_real("torque_measurement_noise", &torque_measurement_noise, 0.0, kOptionHuge,
                 "std of Gaussian noise on observed joint torques [N.m]");
  table.add_real("imu_accelerometer_bias", &imu_accelerometer_bias, 0.0, kOptionHuge,
                 "accelerometer bias components drawn in U(-it, it) at reset [m/s^2]");
  table.add_real("imu_accelerometer_noise", &imu_accelerometer_noise, 0.0, kOptionHuge,
                 "std of accelerometer white noise [m/s^2]");
  table.add_real("imu_gyroscope_bias", &imu_gyroscope_bias, 0.0, kOptionHuge,
                 "gyroscope bias components drawn in U(-it, it) at reset [rad/s]");
  for (int axis = 0; axis < 3; ++axis) {
    table.add_real(std::string("imu_gyroscope_bias_fixed_") + "xyz"[axis],
                   &imu_gyroscope_bias_fixed[axis], -1.0, 1.0,
                   std::string("fixed gyroscope bias about the IMU's ") + "xyz"[axis] +
                       " axis, added to the drawn one [rad/s]");
  }
  table.add_real("imu_gyroscope_noise", &imu_gyroscope_noise, 0.0, kOptionHuge,
                 "std of gyroscope white noise (it reaches the pitch rate) [rad/s]");
  table.add_real("floor_friction", &floor_friction, 0.01, 100.0,
                 "factor on the tire-floor friction");
  table.add_real("torque_limit_scale", &torque_limit_scale, 0.1, 2.0,
                 "factor on every servo's torque limit (0.8: a motor 20 % weaker)");
  table.add_real("floor_friction_variation", &floor_friction_variation, 0.0, 0.99,
                 "tire-floor friction times 1 + U(-it, it), drawn at reset");
  table.add_real("slope_pitch", &slope_pitch, -kMaxSlopeDegrees, kMaxSlopeDegrees,
                 "floor slope about the robot's initial lateral axis, positive facing uphill "
                 "(gravity tilted; the IMU reads it as on a real slope) [deg]");
  table.add_real("slope_roll", &slope_roll, -kMaxSlopeDegrees, kMaxSlopeDegrees,
                 "floor slope about the robot's initial forward axis, positive when the floor "
                 "rises to its left [deg]");
  table.add_real("payload_mass", &payload_mass, 0.0, kMaxPayloadMass,
                 "point mass rigidly attached to the base [kg]");
  const std::string offset_help = "payload offset from the base's centre of mass, ";
  table.add_real("payload_offset_x", &payload_offset_x, -kMaxPayloadOffset, kMaxPayloadOffset,
                 offset_help + "forward [m]");
  table.add_real("payload_offset_y", &payload_offset_y, -kMaxPayloadOffset, kMaxPayloadOffset,
                 offset_help + "left [m]");
  table.add_real("payload_offset_z", &payload_offset_z, -kMaxPayloadOffset, kMaxPayloadOffset,
                 offset_help + "up [m]");
  table.add_real("slope_variation", &slope_variation, 0.0, kMaxSlopeDegrees,
                 "floor slope pitch and roll each plus U(-it, it), drawn at reset [deg]");
  table.add_real("payload_mass_variation", &payload_mass_variation, 0.0, kMaxPayloadMass,
                 "payload mass plus U(0, it), drawn at reset [kg]");
  table.add_real("payload_offset_variation", &payload_offset_variation, 0.0, kMaxPayloadOffset,
                 "payload forward and left offsets each plus U(-it, it), drawn at reset [m]");
  table.add_real("torque_limit_variation", &torque_limit_variation, 0.0, 0.9,
                 "servo torque limits times 1 - U(0, it), drawn at reset");
  table.add_real("bump_share", &bump_share, 0.0, 1.0,
                 "share of episodes whose floor has the bumps (bump_height), drawn at reset; "
                 "the others are flat");
  table.add_real("push_force", &push.force, 0.0, kOptionHuge,
                 "largest push on the base [N], 0 for no pushes");
  table.add_real("push_force_min", &push.force_min, 0.0, kOptionHuge,
                 "smallest push [N]; magnitudes drawn in U(push_force_min, push_force)");
  table.add_real("push_duration", &push.duration, 1e-6, kOptionHuge, "duration of a push [s]");
  table.add_real("push_start", &push.start, 0.0, kOptionHuge, "start of the first push window [s]");
  table.add_real("push_interval", &push.interval, 1e-6, kOptionHuge,
                 "one push at a random time in each window of this length [s]");
  table.add_choice("push_direction", &push.direction,
                   {{"sagittal", PushDirection::kSagittal},
                    {"forward", PushDirection::kForward},
                    {"backward", PushDirection::kBackward},
                    {"lateral", PushDirection::kLateral},
                    {"any", PushDirection::kAny}},
                   "direction of pushes relative to the robot's heading");
  table.add_real("push_sagittal_share", &push.sagittal_share, 0.0, 1.0,
                 "with push_direction any, the share of pushes along the heading (forward or "
                 "back), the rest in any direction");
  table.add_rule([this] { return problem(); });
}

std::string PerturbationSettings::problem() const {
  if (push.enabled() && push.force_min > push.force) {
    return "push_force_min (" + std::to_string(push.force_min) + " N) is above push_force (" +
           std::to_string(push.force) + " N)";
  }
  if (push.enabled() && push.duration > push.interval) {
    return "push_duration (" + std::to_string(push.duration) +
           " s) is longer than push_interval (" + std::to_string(push.interval) + " s)";
  }
  if (push.sagittal_share > 0.0 && push.direction != PushDirection::kAny) {
    return "push_sagittal_share applies to push_direction any only";
  }
  return "";
}

void PerturbationSettings::validate() const { throw_problem(problem()); }

}  // namespace upkie_rl
