#include "cli/drive_loop.hpp"

#include <chrono>
#include <cmath>
#include <iostream>
#include <stdexcept>
#include <string>
#include <thread>

#include "sim/base_observer.hpp"

namespace upkie_rl::apps {

namespace {

/// How often a paused run looks at the page's inputs.
constexpr auto kPausePoll = std::chrono::milliseconds(10);

}  // namespace

VelocityEnv& drive_velocity_env(Env& env, const std::string& env_id) {
  VelocityEnv* velocity = find_velocity_env(env);
  if (velocity == nullptr) {
    throw std::invalid_argument("drive needs a velocity task (Upkie-*-Velocity), not " + env_id);
  }
  return *velocity;
}

DriveLoop::DriveLoop(Env& env, VelocityEnv& velocity, Controller& controller, LiveView& view,
                     DriveControl& drive, EpisodeRecorder* recorder,
                     const DriveLoopSettings& settings)
    : env_(env),
      velocity_(velocity),
      controller_(controller),
      view_(view),
      drive_(drive),
      recorder_(recorder),
      settings_(settings),
      observation_(env.observation_space().size()),
      action_(env.action_space().size()) {}

void DriveLoop::start_episode() {
  ++episode_;
  ++summary_.episodes;
  length_ = 0;
  episode_return_ = 0.0;
  env_.reset(settings_.seed + static_cast<std::uint64_t>(episode_), observation_);
  controller_.reset();
  view_.start_episode(episode_);
}

DriveSummary DriveLoop::run(const std::atomic<bool>& stop) {
  // Standing still until a page drives.
  velocity_.set_command_override(velocity_.command_ranges().rest_command());
  start_episode();
  while (!stop.load()) {
    if (settings_.duration > 0.0 && summary_.simulated_time >= settings_.duration) break;
    controller_.act(observation_, action_);
    write_velocity_fields(velocity_.command(), velocity_.measured_velocity(), view_fields_);
    view_.publish(*env_.full_observation(), length_, episode_return_, action_, view_fields_);
    // Taken after the wait for the wall clock, right before the step: a command that
    // arrived meanwhile is in the very next observation.
    DriveInputs inputs;
    if (!take_inputs(stop, inputs)) break;
    if (inputs.new_command) {
      VelocityCommand command{inputs.forward_velocity, inputs.yaw_rate, inputs.height};
      if (!velocity_.command_ranges().height_command) {
        command.height = velocity_.command_ranges().rest_command().height;
      }
      velocity_.set_command_override(command);
    }
    // A push taken with a reset acts on the new episode rather than being lost.
    if (inputs.reset) start_episode();
    if (inputs.push_heading) push(*inputs.push_heading);
    if (!inputs.reset) step();
    // The controller acts on the observation that holds the command now.
    drive_.applied(inputs, std::chrono::steady_clock::now());
  }
  return summary_;
}

bool DriveLoop::take_inputs(const std::atomic<bool>& stop, DriveInputs& inputs) {
  inputs = drive_.take();
  if (!inputs.paused) return true;
  while (inputs.paused) {
    if (stop.load()) return false;
    std::this_thread::sleep_for(kPausePoll);
    DriveInputs next = drive_.take();
    // Requests made while paused are kept for the step after the pause (pushes wait in
    // DriveControl).
    next.new_command = next.new_command || inputs.new_command;
    next.reset = next.reset || inputs.reset;
    inputs = next;
  }
  view_.restart_pacing();
  return true;
}

void DriveLoop::push(double heading) {
  const double direction =
      base_yaw(env_.full_observation()->base_orientation.rotation_base_to_world) + heading;
  const Eigen::Vector3d force(settings_.push_force * std::cos(direction),
                              settings_.push_force * std::sin(direction), 0.0);
  if (velocity_.servos().push_base(force, settings_.push_duration)) {
    ++summary_.pushes;
    std::cout << "push: " << settings_.push_force << " N for " << settings_.push_duration
              << " s toward " << heading << " rad in the robot's frame" << std::endl;
  }
}

void DriveLoop::step() {
  if (recorder_ != nullptr) recorder_->before_step(env_, observation_);
  const StepResult result = env_.step(action_, observation_);
  if (recorder_ != nullptr) recorder_->after_step(episode_, length_, action_, result);
  episode_return_ += result.reward;
  ++length_;
  ++summary_.steps;
  summary_.simulated_time += env_.timestep();
  if (!(result.terminated || result.truncated)) return;
  if (result.terminated) ++summary_.falls;
  std::cout << "episode " << episode_ << ": "
            << (result.terminated
                    ? std::string("fell (") + to_string(velocity_.termination_reason()) + ")"
                    : std::string("truncated"))
            << " after " << length_ * env_.timestep() << " s, return " << episode_return_
            << "; a new episode starts" << std::endl;
  start_episode();
}

}  // namespace upkie_rl::apps
