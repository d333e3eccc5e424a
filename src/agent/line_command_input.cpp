#include "agent/line_command_input.hpp"

#include <poll.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <string_view>

#include "envs/records/number_row.hpp"

namespace upkie_rl {

std::optional<VelocityCommand> LineCommandInput::parse_line() const {
  const std::string_view line(line_.data(), length_);
  if (line.find_first_not_of(" \t\r") == std::string_view::npos || line.front() == '#') {
    return std::nullopt;
  }
  std::array<double, 3> values{0.0, 0.0, kStandingBaseHeight};
  const bool with_height = parse_number_row(line, values);
  if (!(with_height || parse_number_row(line, std::span<double>(values).first(2))) ||
      !std::isfinite(values[0]) || !std::isfinite(values[1]) || !std::isfinite(values[2])) {
    spdlog::warn(
        "commands: ignored the line '{}' of the standard input: expected vx,wz or vx,wz,height "
        "(finite numbers, m/s, rad/s and m)",
        line);
    return std::nullopt;
  }
  if (!with_height) values[2] = kStandingBaseHeight;
  return VelocityCommand{values[0], values[1], values[2]};
}

std::optional<VelocityCommand> LineCommandInput::poll(double /*time*/) {
  std::optional<VelocityCommand> latest;
  std::array<char, 256> chunk{};
  while (!ended_) {
    pollfd ready{fd_, POLLIN, 0};
    if (::poll(&ready, 1, 0) <= 0) break;  // nothing to read now
    const ssize_t count = ::read(fd_, chunk.data(), chunk.size());
    if (count < 0 && (errno == EINTR || errno == EAGAIN)) break;
    if (count <= 0) {
      ended_ = true;
      spdlog::info("commands: end of the standard input; the last command holds");
      break;
    }
    for (ssize_t i = 0; i < count; ++i) {
      const char character = chunk[static_cast<std::size_t>(i)];
      if (character != '\n') {
        if (length_ == line_.size()) overlong_ = true;
        if (!overlong_) line_[length_++] = character;
        continue;
      }
      if (overlong_) {
        spdlog::warn("commands: ignored a line of the standard input longer than {} characters",
                     kMaxLine);
      } else if (const auto command = parse_line()) {
        latest = command;
      }
      length_ = 0;
      overlong_ = false;
    }
  }
  return latest;
}

}  // namespace upkie_rl
