#include "agent/velocity_commander.hpp"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>

#include "agent/keyboard_command_input.hpp"
#include "agent/line_command_input.hpp"
#include "agent/scheduled_command_input.hpp"

namespace upkie_rl {

VelocityCommander::VelocityCommander(VelocityEnv& env, std::unique_ptr<VelocityCommandInput> input,
                                     const VelocityCommandRanges& trained)
    : env_(env), input_(std::move(input)), trained_(trained) {}

void VelocityCommander::start() {
  std::optional<VelocityCommand> first;
  if (input_) first = input_->poll(0.0);
  apply(first.value_or(trained_.rest_command()), 0.0);
}

void VelocityCommander::update(double time) {
  if (!input_) return;
  if (const std::optional<VelocityCommand> next = input_->poll(time)) apply(*next, time);
}

VelocityCommand clamp_to_trained(const VelocityCommand& wanted,
                                 const VelocityCommandRanges& trained) {
  VelocityCommand command;
  command.forward_velocity = std::clamp(wanted.forward_velocity, -trained.max_forward_velocity,
                                        trained.max_forward_velocity);
  command.yaw_rate = std::clamp(wanted.yaw_rate, -trained.max_yaw_rate, trained.max_yaw_rate);
  // A policy without a height command stands at the height it was trained at.
  command.height = trained.height_command
                       ? std::clamp(wanted.height, trained.min_height, trained.max_height)
                       : trained.rest_command().height;
  return command;
}

void VelocityCommander::apply(const VelocityCommand& wanted, double time) {
  const VelocityCommand command = clamp_to_trained(wanted, trained_);
  if (command != wanted && trained_.height_command) {
    spdlog::warn(
        "commands: ({} m/s, {} rad/s, {} m) clamped to the trained ranges +-{} m/s, +-{} rad/s "
        "and [{}, {}] m",
        wanted.forward_velocity, wanted.yaw_rate, wanted.height, trained_.max_forward_velocity,
        trained_.max_yaw_rate, trained_.min_height, trained_.max_height);
  } else if (command.forward_velocity != wanted.forward_velocity ||
             command.yaw_rate != wanted.yaw_rate) {
    spdlog::warn(
        "commands: ({} m/s, {} rad/s) clamped to the trained ranges +-{} m/s and +-{} rad/s",
        wanted.forward_velocity, wanted.yaw_rate, trained_.max_forward_velocity,
        trained_.max_yaw_rate);
  }
  env_.set_command_override(command);
  spdlog::info(
      "command at {:.2f} s from {}: forward velocity {} m/s, yaw rate {} rad/s, height {} m", time,
      input_ ? input_->name() : std::string("no input (stand still)"), command.forward_velocity,
      command.yaw_rate, command.height);
}

std::unique_ptr<VelocityCommandInput> make_command_input(const RunnerOptions& options) {
  if (options.keyboard) return std::make_unique<KeyboardCommandInput>(STDIN_FILENO);
  if (options.commands == "-") return std::make_unique<LineCommandInput>(STDIN_FILENO);
  if (!options.commands.empty()) return std::make_unique<ScheduledCommandInput>(options.commands);
  return nullptr;
}

}  // namespace upkie_rl
