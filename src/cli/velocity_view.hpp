#pragma once
/// @file
/// What the viewer shows of a velocity task beside the robot: the command and the measured
/// base velocity, as extra frame fields and two charts (live rollouts, `drive`, replays).

#include <span>

#include "envs/tasks/velocity_command.hpp"
#include "view/view_session.hpp"

namespace upkie_rl::apps {

/// Number of extra fields add_velocity_charts adds.
inline constexpr std::size_t kVelocityViewFields = 4;

/// Adds the extra fields (kCommandColumns then kMeasuredVelocityColumns) and the charts
/// "Forward velocity [m/s]" and "Yaw rate [rad/s]", each command against measured.
void add_velocity_charts(ViewSession& session);

/// Writes the extra fields of add_velocity_charts. @pre extra.size() == kVelocityViewFields.
void write_velocity_fields(const VelocityCommand& command, const BaseVelocity& measured,
                           std::span<double> extra);

}  // namespace upkie_rl::apps
