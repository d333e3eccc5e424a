#pragma once
/// @file
/// Whether a tire slipped just before a logged cycle, from what a robot measures: the
/// accelerometer against the wheels' rolling.
///
/// Why: a replay starts from the no-slip base velocity (measured_reset_state), which is
/// wrong by the slip when a tire slips at its first cycle. On a 60 s Bullet log of the
/// excitation (seed 1, hidden friction 0.6), 8 of the 100 replays started more than 2 cm/s
/// off, and moving those starts off the slip (on the simulation's true velocity) lowered
/// the prediction error at the hidden values from 0.0765 to 0.047, as low as starting every
/// replay from the true velocity (0.045).

#include <cstddef>
#include <span>
#include <vector>

#include "envs/records/robot_log.hpp"
#include "model/robot_model.hpp"

namespace upkie_rl {

/// Whether `log` holds accelerometer readings (a spine log's imu.raw_linear_acceleration;
/// a log without them reads zero at every cycle).
bool logs_accelerometer(const RobotLog& log);

/// For each cycle index of `cycles`, the horizontal gap [m/s] between two measures of the
/// IMU's velocity change over the `span` seconds before it: the accelerometer's mean
/// accelerations (gravity removed with the logged attitude) integrated over the cycles,
/// and the change of the IMU's velocity if both tires rolled without slipping. The two
/// agree unless a tire slipped (or the robot left the floor) in that span; cycles with
/// less than `span` of log before them get 0. Requires logs_accelerometer(log).
///
/// On a real robot the accelerometer's bias b adds at most |b| x span (0.3 m/s^2 over
/// 20 ms: 6 mm/s) and its noise averages over the span's cycles.
std::vector<double> tire_slip_evidence(const RobotModel& model, const RobotLog& log,
                                       std::span<const std::size_t> cycles, double span,
                                       double gravity);

}  // namespace upkie_rl
