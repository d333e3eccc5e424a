#pragma once
/// @file
/// The nested-dictionary view of an Observation, with the key names the Upkie spine
/// writes (docs/spine.md; declared once in sim/observation_fields.hpp): as a JSON tree for logs and
/// `info`, and as msgpack for the spine link. Neither is built on the step path; the msgpack writer
/// packs straight from the struct into a caller-owned buffer, without an intermediate tree.
///
/// Fields the spine writes but the typed Observation does not carry get these simulated
/// values (documented here so users know they are not measured):
/// - `servo.<joint>.d_current`, `servo.<joint>.q_current`: 0.0 [A] (no motor model);
/// - `servo.<joint>.fault`: integer 0 (no fault);
/// - `servo.<joint>.mode`: integer 10, moteus' position mode (a backend that reports an
///   observation is servoing; stopped servos are not observed);
/// - `imu.raw_angular_velocity`: equal to `imu.angular_velocity` (no gyro bias simulated);
/// - `floor_contact.upper_leg_torque`: instantaneous Euclidean norm of the hip and knee
///   torques [N.m] (the real observer low-pass filters it with a 10 ms period);
/// - `floor_contact.{left,right}_wheel.{abs_acceleration, abs_torque, contact, inertia}`:
///   abs_acceleration 0.0, abs_torque = |wheel torque| [N.m], contact = the robot's
///   `floor_contact.contact`, inertia 0.0 (the real observer's filters are not simulated);
/// - `sim.imu.linear_velocity`: the base origin's linear velocity in the world frame [m/s]
///   (the IMU is 0.1 m from the base origin: off by |omega x r|).
/// The `sim` subtree is written only when Observation::has_sim is true.
///
/// Wire format: maps with keys in sorted (byte-wise) order, every real number as
/// float64, booleans as booleans, fault and mode as integers, vectors as arrays,
/// quaternions as [w, x, y, z], 3x3 matrices as 9 floats in row-major order.

#include <msgpack.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sim/observation.hpp"
#include "sim/observation_fields.hpp"

namespace upkie_rl {

/// One key of the observation dictionary, as declared in sim/observation_fields.hpp.
struct ObservationKey {
  std::string path;  ///< Dotted, e.g. "servo.left_hip.position".
  bool is_map;       ///< A nested map (its keys follow it, with its path as prefix).
  bool computed;     ///< Written only: the typed Observation does not carry it.
  bool required;     ///< A reader refuses a message without it when its map is there.
};

/// Every key of the declaration, maps and leaves, in walk order (the `sim` subtree
/// included). Allocates: for tests, documentation and the Python binding.
std::vector<ObservationKey> observation_keys();

/// The observation as a nested JSON object (allocates; for logs and `info`).
nlohmann::json observation_to_json(const Observation& observation);

/// Packs the observation as a msgpack map into `buffer`, replacing its contents. The
/// buffer keeps its capacity, so reusing one buffer allocates nothing once it has grown
/// to the size of one observation (about 3 kB).
void write_observation_msgpack(const Observation& observation, msgpack::sbuffer& buffer);

/// Appends the observation map to `buffer` (for messages that embed it).
void pack_observation(const Observation& observation, msgpack::sbuffer& buffer);

}  // namespace upkie_rl
