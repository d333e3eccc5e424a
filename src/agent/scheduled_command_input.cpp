#include "agent/scheduled_command_input.hpp"

#include "envs/core/shared_options.hpp"

namespace upkie_rl {

namespace {

/// The widest ranges a velocity task accepts (its options' upper bound): the file's rows are
/// refused beyond them, then VelocityCommander clamps them to the trained ranges, as it does
/// every input's.
VelocityCommandRanges widest_command_ranges() {
  VelocityCommandRanges ranges;
  ranges.max_forward_velocity = kOptionHuge;
  ranges.max_yaw_rate = kOptionHuge;
  ranges.height_command = true;
  ranges.min_height = kLowestHeightCommand;
  ranges.max_height = kStandingBaseHeight;
  return ranges;
}

}  // namespace

ScheduledCommandInput::ScheduledCommandInput(const std::filesystem::path& path)
    : path_(path), schedule_(VelocityCommandSchedule::load(path, widest_command_ranges())) {}

std::optional<VelocityCommand> ScheduledCommandInput::poll(double time) {
  const VelocityCommand& command = schedule_.at(time);
  if (&command == last_) return std::nullopt;
  last_ = &command;
  return command;
}

}  // namespace upkie_rl
