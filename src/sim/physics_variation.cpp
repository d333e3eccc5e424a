#include "sim/physics_variation.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "base/number_text.hpp"

namespace upkie_rl {
namespace {

void check(bool valid, const std::string& what, double value) {
  if (!valid) {
    throw std::invalid_argument("PhysicsVariation: " + what + " is out of its domain, got " +
                                std::to_string(value));
  }
}

bool finite_non_negative(double value) { return std::isfinite(value) && value >= 0.0; }

bool within(double value, double bound) { return std::isfinite(value) && std::abs(value) <= bound; }

}  // namespace

bool PhysicsVariation::changes_model() const {
  for (const double scale : mass_scale) {
    if (scale != 1.0) return true;
  }
  return floor_friction_scale != 1.0 || tilts_floor() || has_payload() || !floor_bumps;
}

void PhysicsVariation::validate() const {
  for (std::size_t body = 0; body < mass_scale.size(); ++body) {
    check(std::isfinite(mass_scale[body]) && mass_scale[body] > 0.0,
          "mass_scale[" + std::to_string(body) + "] (must be positive)", mass_scale[body]);
  }
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    check(finite_non_negative(joint_friction[servo]),
          "joint_friction of " + std::string(kServoNames[servo]), joint_friction[servo]);
    check(std::isfinite(servo_gain_scale[servo]) && servo_gain_scale[servo] > 0.0,
          "servo_gain_scale of " + std::string(kServoNames[servo]) + " (must be positive)",
          servo_gain_scale[servo]);
  }
  check(finite_non_negative(torque_control_noise), "torque_control_noise", torque_control_noise);
  check(finite_non_negative(torque_measurement_noise), "torque_measurement_noise",
        torque_measurement_noise);
  check(std::isfinite(floor_friction_scale) && floor_friction_scale > 0.0,
        "floor_friction_scale (must be positive)", floor_friction_scale);
  check(std::isfinite(torque_limit_scale) && torque_limit_scale > 0.0,
        "torque_limit_scale (must be positive)", torque_limit_scale);
  // Named as the environment options; the slopes are in radians here.
  const double max_slope = degrees_to_radians(kMaxSlopeDegrees);
  const std::string slope_domain =
      " [rad] (must be within +-" + shortest_text(kMaxSlopeDegrees) + " deg)";
  check(within(slope_pitch, max_slope), "slope_pitch" + slope_domain, slope_pitch);
  check(within(slope_roll, max_slope), "slope_roll" + slope_domain, slope_roll);
  check(finite_non_negative(payload_mass) && payload_mass <= kMaxPayloadMass,
        "payload_mass (must be in [0, " + shortest_text(kMaxPayloadMass) + "] kg)", payload_mass);
  for (int axis = 0; axis < 3; ++axis) {
    check(within(payload_offset[axis], kMaxPayloadOffset),
          std::string("payload_offset_") + "xyz"[axis] + " (must be within +-" +
              shortest_text(kMaxPayloadOffset) + " m)",
          payload_offset[axis]);
  }
  imu.validate();
}

void ImuUncertainty::validate() const {
  const auto check_vector = [](const Eigen::Vector3d& bias, const char* name) {
    for (int i = 0; i < 3; ++i) {
      if (!std::isfinite(bias[i])) {
        throw std::invalid_argument(std::string("IMU uncertainty: ") + name + "[" +
                                    std::to_string(i) + "] is not finite");
      }
    }
  };
  check_vector(accelerometer_bias, "accelerometer_bias");
  check_vector(gyroscope_bias, "gyroscope_bias");
  for (const auto& [value, name] : {std::pair{accelerometer_noise, "accelerometer_noise"},
                                    std::pair{gyroscope_noise, "gyroscope_noise"}}) {
    if (!finite_non_negative(value)) {
      throw std::invalid_argument(std::string("IMU uncertainty: ") + name +
                                  " must be a finite non-negative deviation, got " +
                                  std::to_string(value));
    }
  }
}

}  // namespace upkie_rl
