#pragma once
/// @file
/// Reading the observation dictionary written by a spine into the typed Observation.

#include <msgpack.hpp>

#include "sim/observation.hpp"

namespace upkie_rl {

/// Fills `observation` from a decoded spine observation map (spine.md section 5).
/// Required: `servo.<joint>.{position, velocity, torque}` for the six joints,
/// `base_orientation.{pitch, angular_velocity}` and `wheel_odometry.{position, velocity}`.
/// Optional keys (`time`, servo temperature and voltage, `imu.*`,
/// `base_orientation.rotation_base_to_world`, `floor_contact.contact`, `sim.base.*`) are
/// read when present and otherwise keep their values in `observation`; has_sim tells
/// whether `sim.base` was there. Numbers may be int, float32 or float64. Allocates nothing.
/// @throws SpineError naming the key that is missing or has the wrong type or length.
void read_observation(const msgpack::object& message, Observation& observation);

}  // namespace upkie_rl
