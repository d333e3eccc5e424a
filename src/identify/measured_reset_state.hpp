#pragma once
/// @file
/// The simulation state a logged cycle stands for, from what a robot measures only.

#include "envs/tasks/balance_termination.hpp"
#include "envs/tasks/velocity_task.hpp"
#include "model/robot_model.hpp"
#include "sim/observation.hpp"
#include "sim/reset_state.hpp"

namespace upkie_rl {

/// The state of the robot at a logged observation, from its measurements only: the base
/// orientation, heading included (the IMU's rotation_base_to_world: on Bullet the heading
/// changes how the tires slip), the joint angles and
/// velocities, the base angular velocity (the gyroscope's), and, assuming both tires on a
/// flat floor without slipping, the base height (the lowest tire point at z = 0) and the
/// base's linear velocity (each tire's contact point at rest, averaged over the two tires).
/// Base x and y are 0: the floor is the same everywhere.
ResetState measured_reset_state(const RobotModel& model, const Observation& observation);

/// A base tilted beyond it has fallen [rad] (the balance tasks' fall_pitch): its tires are
/// off the floor, and the no-slip state above does not hold.
inline constexpr double kFallenTilt = BalanceTermination{}.fall_pitch;

/// Whether the robot of `observation` is down: its base (the IMU) tilted beyond kFallenTilt.
inline bool robot_is_down(const Observation& observation) {
  return VelocityTask::tilt(observation) > kFallenTilt;
}

}  // namespace upkie_rl
