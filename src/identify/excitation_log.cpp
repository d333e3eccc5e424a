#include "identify/excitation_log.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "base/error.hpp"
#include "base/number_text.hpp"
#include "envs/controllers/forward_balance_law.hpp"
#include "envs/controllers/velocity_balancer.hpp"
#include "envs/kinds/ground_velocity_commander.hpp"
#include "envs/registry/env_factory.hpp"
#include "identify/measured_reset_state.hpp"
#include "sim/servo_command_fields.hpp"
#include "spine/spine_log_writer.hpp"

namespace upkie_rl {

namespace {

/// Balance before the log starts [s]: the simulators release the robot above the floor, and
/// a robot's log starts with it standing on its wheels.
constexpr double kSettleTime = 0.5;

/// Random commands, each held for a random time.
class CommandSteps {
 public:
  explicit CommandSteps(const ExcitationSettings& settings)
      : generator_(settings.seed),
        forward_(-settings.amplitude, settings.amplitude),
        yaw_(-settings.yaw_amplitude, settings.yaw_amplitude),
        kick_(-settings.kick_amplitude, settings.kick_amplitude),
        hold_(settings.hold_min, settings.hold_max) {}

  /// Draws new commands when the current ones have been held long enough.
  void update(double time) {
    if (time < next_change_) return;
    forward_velocity = forward_(generator_);
    yaw_rate = yaw_(generator_);
    kick = kick_(generator_);
    next_change_ = time + hold_(generator_);
  }

  double forward_velocity = 0.0;
  double yaw_rate = 0.0;
  double kick = 0.0;

 private:
  std::mt19937_64 generator_;
  std::uniform_real_distribution<double> forward_;
  std::uniform_real_distribution<double> yaw_;
  std::uniform_real_distribution<double> kick_;
  std::uniform_real_distribution<double> hold_;
  double next_change_ = 0.0;
};

}  // namespace

void write_excitation_log(const std::string& env_id, const EnvOptions& options,
                          const ExcitationSettings& settings, const std::filesystem::path& path) {
  std::unique_ptr<Env> env = make_env(env_id, options);
  if (env->action_space().size() != kNumServos * kServoCommandFields.size()) {
    throw std::invalid_argument("write_excitation_log: " + env_id + " is not a servos environment");
  }
  std::vector<float> observation(env->observation_space().size());
  std::vector<float> flat(env->action_space().size());
  env->reset(settings.seed, observation);
  const Observation* full = env->full_observation();
  const std::shared_ptr<const RobotModel> model = RobotModel::default_model();
  const double timestep = env->timestep();
  GroundVelocityCommander commander(*model, timestep);
  commander.reset(*full);
  ForwardBalanceLaw balance = VelocityBalancer::forward_law(settings.balance, timestep);
  CommandSteps commands(settings);
  SpineLogWriter writer(path);
  const int settle_steps = static_cast<int>(std::lround(kSettleTime / timestep));
  const int steps = settle_steps + static_cast<int>(settings.duration / timestep);
  for (int i = 0; i < steps; ++i) {
    const bool logged = i >= settle_steps;
    if (logged) commands.update((i - settle_steps) * timestep);
    balance.set_excitation(commands.kick);
    const double ground_velocity =
        balance.ground_velocity({.command = commands.forward_velocity,
                                 .pitch = full->base_orientation.pitch,
                                 .pitch_rate = full->base_orientation.angular_velocity.y(),
                                 .odometry_velocity = full->wheel_odometry.velocity});
    const ServoAction& command = commander.command(ground_velocity, commands.yaw_rate);
    ServoAction sent{};
    for (std::size_t servo = 0; servo < kNumServos; ++servo) {
      for (std::size_t field = 0; field < kServoCommandFields.size(); ++field) {
        const auto member = kServoCommandFields[field].member;
        const float value = static_cast<float>(command[servo].*member);
        flat[servo * kServoCommandFields.size() + field] = value;
        sent[servo].*member = value;  // what the environment receives, to float precision
      }
    }
    if (logged) writer.write(*full, sent);
    env->step(flat, observation);
    full = env->full_observation();
    if (robot_is_down(*full)) {
      throw Error("write_excitation_log: the simulated robot fell at " + shortest_text(full->time) +
                  " s of " + env_id + ": lower the amplitudes or lighten its hidden physics");
    }
  }
  writer.close();
}

}  // namespace upkie_rl
