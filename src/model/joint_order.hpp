#pragma once
/// @file
/// The six actuated joints of Upkie, in the order used everywhere: servo ids 1..6,
/// joint-configuration vectors, observation and action vectors.

#include <array>
#include <cstddef>
#include <string_view>

namespace upkie_rl {

/// Number of actuated joints (servos) of Upkie.
inline constexpr std::size_t kNumServos = 6;

/// Joint names in the standard order.
inline constexpr std::array<std::string_view, kNumServos> kServoNames = {
    "left_hip", "left_knee", "left_wheel", "right_hip", "right_knee", "right_wheel"};

/// Indices of the joints in the standard order.
enum ServoIndex : std::size_t {
  kLeftHip = 0,
  kLeftKnee = 1,
  kLeftWheel = 2,
  kRightHip = 3,
  kRightKnee = 4,
  kRightWheel = 5,
};

/// True for the two wheel joints (continuous, velocity-controlled).
constexpr bool is_wheel(std::size_t servo) { return servo == kLeftWheel || servo == kRightWheel; }

}  // namespace upkie_rl
