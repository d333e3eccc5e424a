#pragma once
/// @file
/// The action message of the spine link:
/// {"servo": {joint: {feedforward_torque, kd_scale, kp_scale, maximum_torque, position,
/// velocity}}}, every value a float64 (NaN position allowed).

#include <msgpack.hpp>

#include "sim/servo_command.hpp"
#include "spine/dictionary.hpp"

namespace upkie_rl {

/// Packs the action message into `buffer`, replacing its contents (keys sorted, values
/// float64). Reusing the buffer allocates nothing once it has grown.
void write_servo_action_msgpack(const ServoAction& action, msgpack::sbuffer& buffer);

/// The action every servo gets when the spine resets (spine.md section 4): position NaN,
/// velocity 0, feedforward 0, gain scales 1, maximum torque 1.0 N.m.
ServoAction spine_default_servo_action();

/// Reads the servo commands of the spine's persistent action dictionary into `action`:
/// fields the dictionary lacks keep their values in `action`.
/// @throws SpineError when a field is not a number, or (with `maximum_torques`) when a
///         maximum_torque is not within [0, the joint's effort] (a stop on the real robot).
void read_servo_action(const Dictionary& dictionary, ServoAction& action,
                       const std::array<double, kNumServos>* maximum_torques = nullptr);

}  // namespace upkie_rl
