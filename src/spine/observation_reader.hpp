#pragma once
/// @file
/// Reading the observation dictionary written by a spine into the typed Observation.

#include <msgpack.hpp>

#include "sim/observation.hpp"

namespace upkie_rl {

/// Fills `observation` from a decoded spine observation map (docs/spine.md), walking the
/// declaration of sim/observation_fields.hpp, which says which keys are required:
/// `servo.<joint>.{position, velocity, torque}` for the six joints,
/// `base_orientation.{pitch, angular_velocity}`, `wheel_odometry.{position, velocity}` and,
/// when `sim` is there, `sim.base.position`. Optional keys (`time`, servo temperature and
/// voltage, `imu.*`, `base_orientation.rotation_base_to_world`, `floor_contact.contact`, the
/// rest of `sim.base.*`) are read when present and otherwise keep their values in
/// `observation`; has_sim tells whether `sim` was there. Keys the writer computes
/// (`imu.raw_angular_velocity`, `floor_contact.upper_leg_torque`, ...) are not read.
/// Numbers may be int, float32 or float64. Allocates nothing.
/// @throws SpineError naming the key that is missing or has the wrong type or length (a
///         present map key whose value is not a map included).
void read_observation(const msgpack::object& message, Observation& observation);

}  // namespace upkie_rl
