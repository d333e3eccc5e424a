#include "envs/registry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string_view>

#include "envs/env_settings.hpp"
#include "envs/observation_noise.hpp"
#include "envs/servos_env.hpp"
#include "envs/time_limit.hpp"
#include "envs/velocity_env.hpp"

namespace upkie_rl {

namespace {

using Backend = EnvBackend;
using Kind = EnvKind;

struct BackendName {
  std::string_view name;
  Backend backend;
};
struct KindName {
  std::string_view name;
  Kind kind;
};

constexpr std::array<BackendName, 4> kBackends = {{
    {"Bullet", Backend::kBullet},
    {"MuJoCo", Backend::kMujoco},
    {"Mock", Backend::kMock},
    {"Spine", Backend::kSpine},
}};
constexpr std::array<KindName, 5> kKinds = {{{"Servos", Kind::kServos},
                                             {"Pendulum", Kind::kPendulum},
                                             {"Gyropod", Kind::kGyropod},
                                             {"ServosTask", Kind::kServosTask},
                                             {"Velocity", Kind::kVelocity}}};

std::string registered_list() {
  std::string list;
  for (const std::string& id : registered_env_ids()) list += (list.empty() ? "" : ", ") + id;
  return list;
}

constexpr double kHuge = 1e9;

void add_balance_options(OptionTable& table, BalanceRewardWeights& reward,
                         BalanceTermination& termination) {
  table.add_double("fall_pitch", &termination.fall_pitch, 0.0, kHuge,
                   "terminate when |pitch| exceeds it [rad]");
  table.add_double("max_position_drift", &termination.max_position_drift, 0.0, kHuge,
                   "terminate when |p - p0| exceeds it [m]");
  table.add_double("max_angular_velocity", &termination.max_angular_velocity, 0.0, kHuge,
                   "terminate when |pitch rate| exceeds it [rad/s]");
  table.add_double("max_linear_velocity", &termination.max_linear_velocity, 0.0, kHuge,
                   "terminate when |ground velocity| exceeds it [m/s]");
  table.add_double("w_theta", &reward.w_theta, -kHuge, kHuge, "reward weight of pitch^2");
  table.add_double("w_theta_dot", &reward.w_theta_dot, -kHuge, kHuge,
                   "reward weight of pitch rate^2");
  table.add_double("w_p_dot", &reward.w_p_dot, -kHuge, kHuge, "reward weight of ground velocity^2");
  table.add_double("w_a", &reward.w_a, -kHuge, kHuge, "reward weight of action^2");
  table.add_double("w_s", &reward.w_s, -kHuge, kHuge, "reward weight of (action change)^2");
  table.add_double("w_accel", &reward.w_accel, -kHuge, kHuge,
                   "reward weight of (second action difference)^2");
}

constexpr double kVelocityFrequency = 50.0;  // [Hz]
constexpr int kVelocityEpisodeSteps = 1000;  // 20 s

void add_velocity_options(OptionTable& table, VelocityTaskConfig& task,
                          VelocityCommandRanges& commands) {
  table.add_double("max_forward_velocity", &commands.max_forward_velocity, 0.0, kHuge,
                   "random forward velocity commands in +-it [m/s]");
  table.add_double("max_yaw_rate", &commands.max_yaw_rate, 0.0, kHuge,
                   "random yaw rate commands in +-it [rad/s]");
  table.add_double("zero_command_probability", &commands.zero_command_probability, 0.0, 1.0,
                   "share of random commands that ask to stand still");
  table.add_double("command_resample_time_min", &commands.resample_time_min, 0.0, kHuge,
                   "a random command holds U(min, max) seconds [s]");
  table.add_double("command_resample_time_max", &commands.resample_time_max, 0.0, kHuge,
                   "longest hold of a random command [s], 0 for one command per episode");
  table.add_double("wheel_velocity_scale", &task.wheel_velocity_scale, 1e-6, kHuge,
                   "wheel velocity target at action 1 [rad/s]");
  table.add_double("leg_action_scale", &task.leg_action_scale, 1e-6, 10.0,
                   "hip and knee target offset from the default pose at action 1 [rad]");
  table.add_double("leg_kp_scale", &task.leg_kp_scale, 0.0, ServosEnv::kMaxGainScale,
                   "kp_scale of hips and knees");
  table.add_double("leg_kd_scale", &task.leg_kd_scale, 0.0, ServosEnv::kMaxGainScale,
                   "kd_scale of hips and knees");
  table.add_double("wheel_kd_scale", &task.wheel_kd_scale, 0.0, ServosEnv::kMaxGainScale,
                   "kd_scale of the wheels' velocity loop");
  table.add_double("fall_tilt", &task.fall_tilt, 0.0, 3.2,
                   "terminate when the base tilts more than it [rad]");
  table.add_choice(
      "terminate_on_contact", {"true", "false"},
      [&task](std::size_t choice) { task.terminate_on_contact = choice == 0; },
      "terminate when a part other than a wheel touches the floor");
  table.add_string("base_controller", &task.base_controller,
                   "residual mode: a controller spec (balancer:... from `rollout --controller "
                   "lqr`) whose action is added to residual_scale times the agent's");
  table.add_double("residual_scale", &task.residual_scale, 0.0, 1.0,
                   "residual mode: weight of the agent's action");
  VelocityRewardWeights& reward = task.reward;
  table.add_double("w_track_forward_velocity", &reward.w_track_forward_velocity, 0.0, kHuge,
                   "reward weight of forward velocity tracking");
  table.add_double("w_track_yaw_rate", &reward.w_track_yaw_rate, 0.0, kHuge,
                   "reward weight of yaw rate tracking");
  table.add_double("w_upright", &reward.w_upright, 0.0, kHuge, "reward weight of uprightness");
  table.add_double("w_pose", &reward.w_pose, 0.0, kHuge,
                   "reward weight of the legs' closeness to the default pose");
  table.add_double("w_action_rate", &reward.w_action_rate, 0.0, kHuge,
                   "penalty weight of the squared action change");
  table.add_double("forward_velocity_sigma", &reward.forward_velocity_sigma, 1e-6, kHuge,
                   "width of the forward velocity tracking kernel [m/s]");
  table.add_double("yaw_rate_sigma", &reward.yaw_rate_sigma, 1e-6, kHuge,
                   "width of the yaw rate tracking kernel [rad/s]");
}

}  // namespace

EnvId parse_env_id(const std::string& id) {
  constexpr std::string_view kPrefix = "Upkie-";
  const std::string_view view(id);
  const std::size_t dash = view.find('-', kPrefix.size());
  if (view.substr(0, kPrefix.size()) == kPrefix && dash != std::string_view::npos) {
    std::string_view backend = view.substr(kPrefix.size(), dash - kPrefix.size());
    const std::string_view kind = view.substr(dash + 1);
    if (backend == "PyBullet") backend = "Bullet";
    for (const BackendName& b : kBackends) {
      if (b.name != backend) continue;
      for (const KindName& k : kKinds) {
        if (k.name == kind) return EnvId{b.backend, k.kind};
      }
    }
  }
  throw std::invalid_argument("environment id \"" + id +
                              "\" not found; registered ids: " + registered_list() +
                              " (Upkie-PyBullet-* is an alias of Upkie-Bullet-*)");
}

OptionTable env_option_table(const EnvId& id, EnvSettings& settings) {
  const Kind kind = id.kind;
  const bool timed = kind == Kind::kPendulum || kind == Kind::kServosTask;
  settings.max_episode_steps = timed ? 300 : 0;
  if (kind == Kind::kVelocity) {
    // The policy runs at 50 Hz (as mjlab_upkie's); episodes of 20 s. Physics stays at the
    // 1 ms reference on both engines: at 5 ms MuJoCo's wheel velocity loop and tire contact
    // go unstable (the pendulum's balancer falls), at 2 ms the wheel speeds jitter by
    // ±0.5 m/s and the balancer tracks 4x worse than at 1 ms.
    settings.frequency = kVelocityFrequency;
    settings.max_episode_steps = kVelocityEpisodeSteps;
  }
  OptionTable table;
  table.add_double("frequency", &settings.frequency, 1.0, 10000.0, "agent rate [Hz]");
  if (id.backend == Backend::kSpine) {
    SpineBackendConfig& spine = settings.spine;
    table.add_string("shm_name", &spine.shm_name, "shared-memory name of the spine");
    table.add_choice(
        "regulate_frequency", {"true", "false"},
        [&spine](std::size_t choice) { spine.regulate_frequency = choice == 0; },
        "sleep so that actions leave at the agent rate (real-time spines)");
    table.add_double("request_timeout", &spine.request_timeout, 1e-3, 3600.0,
                     "longest wait for the spine to answer [s]");
    table.add_int("open_tries", &spine.open_tries, 1, 1000,
                  "attempts at opening the spine's shared memory, 1 s apart");
  } else {
    table.add_int("nb_substeps", &settings.nb_substeps, 0, 10000,
                  "physics steps per agent step, 0 for round(1000/frequency)");
    table.add_choice(
        "inertia", {"box", "urdf"},
        [&settings](std::size_t choice) {
          settings.inertia_source =
              choice == 0 ? InertiaSource::kBulletBoxRule : InertiaSource::kUrdf;
        },
        "link inertias: Bullet's box rule (as PyBullet) or the URDF tensors");
    if (id.backend != Backend::kMock) {
      const std::size_t first = table.size();
      settings.perturbations.add_options(table);
      table.mark_randomization(first);
    }
  }
  const std::size_t first_noise_option = table.size();
  table.add_double("observation_noise", &settings.observation_noise, 0.0, kHuge,
                   "uniform noise in +-it on every observation component");
  table.add_double("action_lag_min", &settings.action_lag.time_constant_min, 0.0, kHuge,
                   "first-order action lag: time constant drawn in U(min, max) at reset [s]");
  table.add_double("action_lag_max", &settings.action_lag.time_constant_max, 0.0, kHuge,
                   "largest action lag time constant [s], 0 for no lag");
  table.add_int("action_delay", &settings.action_lag.delay_steps, 0, 10000,
                "steps between an action and its application");
  table.mark_randomization(first_noise_option);
  table.add_int("max_episode_steps", &settings.max_episode_steps, 0, 1'000'000'000,
                "truncate episodes after this many steps, 0 for never");
  const std::size_t first_init_option = table.size();
  InitRandomization& init = settings.init_rand;
  table.add_double("init_rand_roll", &init.roll, 0.0, 3.2, "initial roll drawn in +-it [rad]");
  table.add_double("init_rand_pitch", &init.pitch, 0.0, 3.2, "initial pitch drawn in +-it [rad]");
  table.add_double("init_rand_x", &init.x, 0.0, kHuge, "initial x drawn in +-it [m]");
  table.add_double("init_rand_z", &init.z, 0.0, kHuge, "initial height raised by [0, it] [m]");
  table.add_double("init_rand_omega_x", &init.omega_x, 0.0, kHuge,
                   "initial roll rate drawn in +-it [rad/s]");
  table.add_double("init_rand_omega_y", &init.omega_y, 0.0, kHuge,
                   "initial pitch rate drawn in +-it [rad/s]");
  table.add_double("init_rand_v_x", &init.v_x, 0.0, kHuge, "initial x velocity in +-it [m/s]");
  table.add_double("init_rand_v_y", &init.v_y, 0.0, kHuge, "initial y velocity in +-it [m/s]");
  table.add_double("init_rand_v_z", &init.v_z, 0.0, kHuge, "initial z velocity in +-it [m/s]");
  table.mark_randomization(first_init_option);
  switch (kind) {
    case Kind::kServos:
      break;
    case Kind::kPendulum: {
      PendulumConfig& pendulum = settings.pendulum;
      table.add_double("max_ground_velocity", &pendulum.max_ground_velocity, 1e-6, kHuge,
                       "action bound a_max [m/s]");
      table.add_double("leg_gain_scale", &pendulum.leg_gain_scale, 0.0, ServosEnv::kMaxGainScale,
                       "gain scales of the held legs");
      add_balance_options(table, pendulum.reward, pendulum.termination);
      break;
    }
    case Kind::kGyropod: {
      GyropodConfig& gyropod = settings.gyropod;
      table.add_double("max_ground_velocity", &gyropod.max_ground_velocity, 1e-6, kHuge,
                       "ground velocity bound [m/s]");
      table.add_double("max_yaw_velocity", &gyropod.max_yaw_velocity, 1e-6, kHuge,
                       "yaw velocity bound [rad/s]");
      table.add_double("fall_pitch", &gyropod.fall_pitch, 0.0, kHuge,
                       "terminate when |pitch| exceeds it [rad]");
      table.add_double("leg_gain_scale", &gyropod.leg_gain_scale, 0.0, ServosEnv::kMaxGainScale,
                       "gain scales of the held legs");
      break;
    }
    case Kind::kServosTask: {
      ServosTaskConfig& task = settings.task;
      add_balance_options(table, task.reward, task.termination);
      table.add_choice(
          "observe_pitch", {"false", "true"},
          [&task](std::size_t choice) { task.observe_pitch = choice == 1; },
          "append the base pitch and pitch rate (the IMU's) to the 12 joint components");
      table.add_choice(
          "action_magnitude", {"servo", "normalized"},
          [&task](std::size_t choice) {
            task.action_magnitude = choice == 0 ? ServosTaskConfig::ActionMagnitude::kServo
                                                : ServosTaskConfig::ActionMagnitude::kNormalized;
          },
          "|a| of the reward: wheel rad/s + leg rad (seed) or mean |u| of the action");
      table.add_double("max_wheel_velocity", &task.max_wheel_velocity, 0.0, kHuge,
                       "wheel velocity at action 1 [rad/s], 0 for the velocity limit");
      table.add_double("leg_action_scale", &task.leg_action_scale, 1e-3, 1.0,
                       "fraction of each leg joint's range spanned by the action");
      break;
    }
    case Kind::kVelocity:
      add_velocity_options(table, settings.velocity, settings.commands);
      break;
  }
  return table;
}

std::string env_id_name(EnvBackend backend, EnvKind kind) {
  std::string name = "Upkie-";
  for (const BackendName& b : kBackends) {
    if (b.backend == backend) name += std::string(b.name) + "-";
  }
  for (const KindName& k : kKinds) {
    if (k.kind == kind) name += k.name;
  }
  return name;
}

EnvSettings parse_env_settings(const EnvId& id, const std::string& name,
                               const EnvOptions& options) {
  EnvSettings settings;
  env_option_table(id, settings).apply(options, name);
  try {
    settings.perturbations.validate();
    settings.action_lag.validate();
    if (id.kind == Kind::kVelocity) settings.commands.validate();
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument(name + ": " + error.what());
  }
  return settings;
}

SpineBackendConfig spine_backend_config(const EnvSettings& settings) {
  SpineBackendConfig config = settings.spine;
  config.agent_frequency = settings.frequency;
  return config;
}

std::unique_ptr<Env> assemble_env(const EnvId& id, const EnvSettings& settings,
                                  std::unique_ptr<Simulation> simulation,
                                  int physics_steps_per_step) {
  auto servos = std::make_unique<ServosEnv>(std::move(simulation), RobotModel::default_model(),
                                            settings.init_rand, physics_steps_per_step,
                                            settings.perturbations);
  std::unique_ptr<Env> env;
  switch (id.kind) {
    case Kind::kServos:
      env = std::move(servos);
      break;
    case Kind::kPendulum:
      env = std::make_unique<PendulumEnv>(std::move(servos), settings.pendulum);
      break;
    case Kind::kGyropod:
      env = std::make_unique<GyropodEnv>(std::move(servos), settings.gyropod);
      break;
    case Kind::kServosTask:
      env = std::make_unique<ServosTaskEnv>(std::move(servos), settings.task);
      break;
    case Kind::kVelocity:
      env = std::make_unique<VelocityEnv>(std::move(servos), settings.velocity, settings.commands);
      break;
  }
  if (settings.action_lag.any()) {
    env = std::make_unique<ActionLag>(std::move(env), settings.action_lag);
  }
  if (settings.observation_noise > 0.0) {
    env = std::make_unique<ObservationNoise>(std::move(env), settings.observation_noise);
  }
  if (settings.max_episode_steps > 0) {
    env = std::make_unique<TimeLimit>(std::move(env), settings.max_episode_steps);
  }
  return env;
}

std::vector<std::string> registered_env_ids() {
  std::vector<std::string> ids;
  for (const BackendName& backend : kBackends) {
    for (const KindName& kind : kKinds) {
      ids.push_back("Upkie-" + std::string(backend.name) + "-" + std::string(kind.name));
    }
  }
  return ids;
}

std::vector<std::string> env_option_help(const std::string& id) {
  EnvSettings settings;
  return env_option_table(parse_env_id(id), settings).describe();
}

EnvOptions task_options(const std::string& source_id, const EnvOptions& options,
                        const std::string& target_id) {
  const std::vector<OptionInfo> source = env_option_info(source_id);
  const std::vector<OptionInfo> target = env_option_info(target_id);
  const auto find = [](const std::vector<OptionInfo>& list, const std::string& name) {
    return std::find_if(list.begin(), list.end(),
                        [&name](const OptionInfo& info) { return info.name == name; });
  };
  EnvOptions kept;
  for (const auto& [key, value] : options) {
    const auto in_source = find(source, key);
    if (in_source == source.end() || in_source->randomization) continue;
    if (find(target, key) == target.end()) continue;
    kept.emplace_back(key, value);
  }
  return kept;
}

std::vector<OptionInfo> env_option_info(const std::string& id) {
  EnvSettings settings;
  return env_option_table(parse_env_id(id), settings).info();
}

}  // namespace upkie_rl
