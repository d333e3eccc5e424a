#pragma once
/// @file
/// The simulation state a logged cycle stands for, from what a robot measures only.

#include "model/robot_model.hpp"
#include "sim/observation.hpp"
#include "sim/reset_state.hpp"

namespace upkie_rl {

/// The state of the robot at a logged observation, from its measurements only: the base
/// orientation without its yaw (the IMU's rotation_base_to_world), the joint angles and
/// velocities, the base angular velocity (the gyroscope's), and, assuming both tires on a
/// flat floor without slipping, the base height (the lowest tire point at z = 0) and the
/// base's linear velocity (each tire's contact point at rest, averaged over the two tires).
/// Base x and y are 0: the floor is the same everywhere.
ResetState measured_reset_state(const RobotModel& model, const Observation& observation);

}  // namespace upkie_rl
