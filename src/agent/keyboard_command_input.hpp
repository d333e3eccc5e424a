#pragma once
/// @file
/// KeyboardCommandInput: the velocity command steered with the keys of the terminal.

#include <termios.h>

#include <optional>

#include "agent/velocity_command_input.hpp"

namespace upkie_rl {

/// Keys change the command by steps: w or Up faster forward, s or Down faster backward,
/// a or Left turn left (counterclockwise) faster, d or Right turn right faster, r raise and
/// f lower the base (height command), space or 0 stop (zero velocities, the height kept). On a
/// terminal, keys are read as they are pressed (no Enter, no echo; Ctrl-C still interrupts) and the
/// terminal is restored on destruction; from a pipe, the same characters are read as they come.
/// Other keys are ignored.
class KeyboardCommandInput final : public VelocityCommandInput {
 public:
  static constexpr double kForwardStep = 0.1;  ///< [m/s] per key press
  static constexpr double kYawStep = 0.25;     ///< [rad/s] per key press
  static constexpr double kHeightStep = 0.02;  ///< [m] per key press, within a deep crouch
                                               ///< (kLowestHeightCommand) and standing

  /// Reads `fd` (not owned), e.g. 0; prints the keys' meaning.
  /// @throws AgentError when the terminal cannot be set up.
  explicit KeyboardCommandInput(int fd);
  ~KeyboardCommandInput() override;
  KeyboardCommandInput(const KeyboardCommandInput&) = delete;
  KeyboardCommandInput& operator=(const KeyboardCommandInput&) = delete;

  std::optional<VelocityCommand> poll(double time) override;
  std::string name() const override { return "keyboard"; }

 private:
  /// Applies one character; true when it changed the command.
  bool on_key(char key);

  int fd_;
  std::optional<termios> saved_terminal_;
  VelocityCommand command_;
  int escape_ = 0;  ///< Characters of an arrow key's "ESC [ X" sequence seen so far.
  bool ended_ = false;
};

}  // namespace upkie_rl
