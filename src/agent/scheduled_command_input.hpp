#pragma once
/// @file
/// ScheduledCommandInput: the commands of a CSV file (`rollout --commands`'s format).

#include <cstddef>
#include <filesystem>

#include "agent/velocity_command_input.hpp"
#include "envs/tasks/velocity_command_schedule.hpp"

namespace upkie_rl {

/// The rows `time,vx,wz` of a file, each held from its time until the next row's, on the
/// runner's clock (cycles times the task's period), as `upkie-rl rollout --commands` does.
class ScheduledCommandInput final : public VelocityCommandInput {
 public:
  /// @throws std::invalid_argument naming the file and line of a malformed row, or of a value
  ///         beyond any task's range (kOptionHuge); values within it are clamped to the
  ///         trained ranges by VelocityCommander.
  explicit ScheduledCommandInput(const std::filesystem::path& path);

  std::optional<VelocityCommand> poll(double time) override;
  std::string name() const override { return "file " + path_.string(); }

 private:
  std::filesystem::path path_;
  VelocityCommandSchedule schedule_;
  const VelocityCommand* last_ = nullptr;
};

}  // namespace upkie_rl
