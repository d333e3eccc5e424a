#pragma once
/// @file
/// VelocityCommandInput: where the robot runner's velocity commands come from (a file, the
/// standard input, the keyboard of its terminal).

#include <optional>
#include <string>

#include "envs/tasks/velocity_command.hpp"

namespace upkie_rl {

/// A source of velocity-task commands polled once per cycle of the runner's loop.
class VelocityCommandInput {
 public:
  virtual ~VelocityCommandInput() = default;

  /// The command to follow from `time` [s since the run started] on when a new one came
  /// (a line, a key, the schedule's next row), else std::nullopt. Never blocks (the loop keeps its
  /// period) and allocates nothing when nothing changed.
  virtual std::optional<VelocityCommand> poll(double time) = 0;

  /// What the log calls it: "file F", "standard input" or "keyboard".
  virtual std::string name() const = 0;
};

}  // namespace upkie_rl
