#pragma once
/// @file
/// LineCommandInput: commands typed or piped as lines `vx,wz` or `vx,wz,height` (the
/// standard input; without a height: standing).

#include <array>
#include <cstddef>

#include "agent/velocity_command_input.hpp"

namespace upkie_rl {

/// Lines `vx,wz` ([m/s], [rad/s]) read from a file descriptor without blocking; each takes
/// effect at the cycle that reads it and holds until the next. Blank lines and lines
/// starting with '#' are skipped; a malformed or too long line is logged and ignored (the
/// robot keeps its command); at the end of the input the last command holds.
class LineCommandInput final : public VelocityCommandInput {
 public:
  /// Longest line taken [characters].
  static constexpr std::size_t kMaxLine = 200;

  /// Reads `fd` (not owned, left open), e.g. 0 for the standard input.
  explicit LineCommandInput(int fd) : fd_(fd) {}

  std::optional<VelocityCommand> poll(double time) override;
  std::string name() const override { return "standard input"; }

 private:
  /// The command of the line in line_[0, length_) if it is one (or nullopt, logged).
  std::optional<VelocityCommand> parse_line() const;

  int fd_;
  bool ended_ = false;
  bool overlong_ = false;  ///< Inside a line longer than kMaxLine: dropped up to its end.
  std::array<char, kMaxLine> line_{};
  std::size_t length_ = 0;
};

}  // namespace upkie_rl
