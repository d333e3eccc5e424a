#pragma once
/// @file
/// The environment options `upkie-rl identify` fits, declared once with their ranges.

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace upkie_rl {

/// An environment option identification can fit.
struct IdentifiedParameter {
  std::string_view name;  ///< The option (action_lag stands for action_lag_min and _max).
  double low = 0.0;       ///< Declared range: fits stay within it.
  double high = 0.0;
  double nominal = 0.0;  ///< The nominal robot's value, where a fit starts.
  bool integer = false;  ///< Whole numbers only (action_delay, in agent steps).
  std::string_view unit;
  /// Non-empty: why this option cannot be fitted (it names no fixed physical value).
  std::string_view not_fittable;
};

/// The options: masses, payload, floor, motors, actuation timing, sensors, and the ones a fit
/// refuses.
inline constexpr std::array<IdentifiedParameter, 16> kIdentifiedParameters = {{
    {"mass_scale", 0.5, 2.0, 1.0, false, "", ""},
    {"payload_mass", 0.0, 3.0, 0.0, false, "kg", ""},
    {"payload_offset_x", -0.2, 0.2, 0.0, false, "m", ""},
    {"payload_offset_y", -0.2, 0.2, 0.0, false, "m", ""},
    {"payload_offset_z", -0.2, 0.2, 0.0, false, "m", ""},
    {"floor_friction", 0.05, 2.0, 1.0, false, "", ""},
    {"torque_limit_scale", 0.2, 1.5, 1.0, false, "", ""},
    {"action_delay", 0.0, 10.0, 0.0, true, "steps", ""},
    {"action_lag", 0.0, 0.3, 0.0, false, "s", ""},
    {"wheel_servo_gain_scale", 0.3, 3.0, 1.0, false, "", ""},
    {"leg_servo_gain_scale", 0.3, 3.0, 1.0, false, "", ""},
    {"joint_friction_fixed", 0.0, 0.5, 0.0, false, "N.m", ""},
    // The base's pitch axis is the IMU's y axis (the IMU is turned about z and x by pi).
    {"imu_gyroscope_bias_fixed_y", -0.1, 0.1, 0.0, false, "rad/s", ""},
    {"joint_friction", 0.0, 0.0, 0.0, false, "N.m",
     "joint_friction is drawn per joint in U(0, it) at each reset; fit joint_friction_fixed"},
    {"imu_gyroscope_bias", 0.0, 0.0, 0.0, false, "rad/s",
     "imu_gyroscope_bias is drawn in U(-it, it) at each reset; fit imu_gyroscope_bias_fixed_y "
     "(the pitch axis: replays compare the pitch rate only)"},
    {"inertia_variation", 0.0, 0.0, 0.0, false, "",
     "inertia_variation is a randomisation range, not a physical value"},
}};

/// A parameter to fit and the range to search.
struct ParameterRequest {
  const IdentifiedParameter* parameter = nullptr;
  double low = 0.0;
  double high = 0.0;
};

/// Parses `NAME` (its declared range) or `NAME=LOW:HIGH`.
/// @throws std::invalid_argument naming the parameter: unknown (listing the known ones), not
///         fittable (saying why), a range that is not two numbers LOW < HIGH, or one outside
///         the declared range.
ParameterRequest parse_parameter_request(const std::string& text);

/// Parses each of `texts`; none: the default set (mass_scale, floor_friction, action_delay,
/// action_lag).
/// @throws std::invalid_argument as above, or on a parameter named twice.
std::vector<ParameterRequest> parse_parameter_requests(const std::vector<std::string>& texts);

}  // namespace upkie_rl
