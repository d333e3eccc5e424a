#include "agent/keyboard_command_input.hpp"

#include <poll.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <iterator>
#include <string>

#include "agent/agent_error.hpp"
#include "envs/tasks/velocity_command_sampler.hpp"

namespace upkie_rl {

KeyboardCommandInput::KeyboardCommandInput(int fd) : fd_(fd) {
  if (::isatty(fd_) == 1) {
    termios terminal{};
    if (::tcgetattr(fd_, &terminal) != 0) {
      throw AgentError(std::string("keyboard commands: cannot read the terminal's settings: ") +
                       std::strerror(errno));
    }
    saved_terminal_ = terminal;
    terminal.c_lflag &= ~static_cast<tcflag_t>(ICANON | ECHO);  // keys at once, unechoed
    terminal.c_cc[VMIN] = 0;
    terminal.c_cc[VTIME] = 0;
    if (::tcsetattr(fd_, TCSANOW, &terminal) != 0) {
      throw AgentError(std::string("keyboard commands: cannot set up the terminal: ") +
                       std::strerror(errno));
    }
  }
  spdlog::info(
      "keyboard commands: w/Up +{} m/s, s/Down -{} m/s, a/Left +{} rad/s (left), d/Right -{} "
      "rad/s, r/f base height +-{} m, space or 0 stop",
      kForwardStep, kForwardStep, kYawStep, kYawStep, kHeightStep);
}

KeyboardCommandInput::~KeyboardCommandInput() {
  if (saved_terminal_) ::tcsetattr(fd_, TCSANOW, &*saved_terminal_);
}

bool KeyboardCommandInput::on_key(char key) {
  if (escape_ == 0 && key == '\x1b') {
    escape_ = 1;
    return false;
  }
  if (escape_ == 1) {
    escape_ = key == '[' ? 2 : 0;
    return false;
  }
  if (escape_ == 2) {
    escape_ = 0;
    const char arrows[] = {'A', 'B', 'D', 'C'};  // Up, Down, Left, Right
    const char keys[] = {'w', 's', 'a', 'd'};
    const char* found = std::find(std::begin(arrows), std::end(arrows), key);
    if (found == std::end(arrows)) return false;
    key = keys[found - std::begin(arrows)];
  }
  switch (key) {
    case 'w':
      command_.forward_velocity += kForwardStep;
      return true;
    case 's':
      command_.forward_velocity -= kForwardStep;
      return true;
    case 'a':
      command_.yaw_rate += kYawStep;
      return true;
    case 'd':
      command_.yaw_rate -= kYawStep;
      return true;
    case 'r':
      command_.height = std::min(command_.height + kHeightStep, kStandingBaseHeight);
      return true;
    case 'f':
      command_.height = std::max(command_.height - kHeightStep, kLowestHeightCommand);
      return true;
    case ' ':
    case '0':
      command_.forward_velocity = 0.0;
      command_.yaw_rate = 0.0;
      return true;
    default:
      return false;
  }
}

std::optional<VelocityCommand> KeyboardCommandInput::poll(double /*time*/) {
  bool changed = false;
  std::array<char, 64> keys{};
  while (!ended_) {
    pollfd ready{fd_, POLLIN, 0};
    if (::poll(&ready, 1, 0) <= 0) break;
    const ssize_t count = ::read(fd_, keys.data(), keys.size());
    if (count < 0 && (errno == EINTR || errno == EAGAIN)) break;
    if (count <= 0) {
      ended_ = true;  // a closed pipe; a terminal reads 0 only when no key is pending
      break;
    }
    for (ssize_t i = 0; i < count; ++i) changed |= on_key(keys[static_cast<std::size_t>(i)]);
  }
  if (!changed) return std::nullopt;
  // Steps of 0.1 accumulate rounding (0.30000000000000004): commands are kept to 1e-9.
  command_.forward_velocity = std::round(command_.forward_velocity * 1e9) / 1e9;
  command_.yaw_rate = std::round(command_.yaw_rate * 1e9) / 1e9;
  command_.height = std::round(command_.height * 1e9) / 1e9;
  return command_;
}

}  // namespace upkie_rl
