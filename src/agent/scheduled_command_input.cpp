#include "agent/scheduled_command_input.hpp"

namespace upkie_rl {

ScheduledCommandInput::ScheduledCommandInput(const std::filesystem::path& path)
    : path_(path), schedule_(VelocityCommandSchedule::load(path)) {}

std::optional<VelocityCommand> ScheduledCommandInput::poll(double time) {
  const VelocityCommand& command = schedule_.at(time);
  if (&command == last_) return std::nullopt;
  last_ = &command;
  return command;
}

}  // namespace upkie_rl
