#include "identify/excitation_log.hpp"

#include <algorithm>
#include <memory>
#include <random>
#include <vector>

#include "envs/kinds/ground_velocity_commander.hpp"
#include "envs/registry/env_factory.hpp"
#include "sim/servo_command_fields.hpp"
#include "spine/spine_log_writer.hpp"

namespace upkie_rl {

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
  GroundVelocityCommander commander(*RobotModel::default_model(), env->timestep());
  commander.reset(*full);
  SpineLogWriter writer(path);
  std::mt19937_64 generator(settings.seed);
  std::uniform_real_distribution<double> step(-settings.amplitude, settings.amplitude);
  std::uniform_real_distribution<double> hold(settings.hold_min, settings.hold_max);
  double excitation = 0.0;
  double next_change = 0.5;  // a second of balance first
  const double start_position = full->wheel_odometry.position;
  const int steps = static_cast<int>(settings.duration / env->timestep());
  for (int i = 0; i < steps; ++i) {
    const double time = i * env->timestep();
    if (time >= next_change) {
      excitation = step(generator);
      next_change = time + hold(generator);
    }
    const double ground_velocity = std::clamp(10.0 * full->base_orientation.pitch +
                                                  (full->wheel_odometry.position - start_position) +
                                                  0.1 * full->wheel_odometry.velocity + excitation,
                                              -1.0, 1.0);
    const ServoAction& command = commander.command(ground_velocity, 0.0);
    ServoAction sent{};
    for (std::size_t servo = 0; servo < kNumServos; ++servo) {
      for (std::size_t field = 0; field < kServoCommandFields.size(); ++field) {
        const auto member = kServoCommandFields[field].member;
        const float value = static_cast<float>(command[servo].*member);
        flat[servo * kServoCommandFields.size() + field] = value;
        sent[servo].*member = value;  // what the environment receives, to float precision
      }
    }
    writer.write(*full, sent);
    env->step(flat, observation);
    full = env->full_observation();
  }
  writer.close();
}

}  // namespace upkie_rl
