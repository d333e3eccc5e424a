#include "envs/registry/registry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string_view>

#include "base/closest_name.hpp"
#include "base/number_text.hpp"
#include "envs/core/shared_options.hpp"
#include "envs/kinds/servos_env.hpp"
#include "envs/kinds/velocity_env.hpp"
#include "envs/randomization/observation_noise.hpp"
#include "envs/registry/env_settings.hpp"
#include "envs/wrappers/observation_history.hpp"
#include "envs/wrappers/time_limit.hpp"

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

constexpr double kVelocityFrequency = 50.0;  // [Hz]
constexpr int kVelocityEpisodeSteps = 1000;  // 20 s

// The defaults of `kind` that differ from EnvSettings'.
void set_kind_defaults(Kind kind, EnvSettings& settings) {
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
}

// Declares what `declare` adds to `table` as randomisation (OptionInfo::randomization).
template <class Declare>
void declare_randomization(OptionTable& table, Declare declare) {
  const std::size_t first = table.size();
  declare();
  table.mark_randomization(first);
}

// The options of the backend: the spine's, or the physics engine's and its perturbations.
void declare_backend_options(Backend backend, EnvSettings& settings, OptionTable& table) {
  if (backend == Backend::kSpine) {
    settings.spine.declare_options(table);
    return;
  }
  // A condition, not part of the task: a policy trained on a coarser step for speed is
  // rolled out, evaluated and run on the spine at the 1 ms reference unless told otherwise.
  declare_randomization(table, [&] {
    table.add_integer("nb_substeps", &settings.nb_substeps, 0, 10000,
                      "physics steps per agent step, 0 for round(1000/frequency) (the 1 ms "
                      "reference); a training's value is not carried to its rollouts");
  });
  table.add_choice("inertia", &settings.inertia_source,
                   {{"box", InertiaSource::kBulletBoxRule}, {"urdf", InertiaSource::kUrdf}},
                   "link inertias: Bullet's box rule (as PyBullet) or the URDF tensors");
  if (backend != Backend::kMock) {
    declare_randomization(table, [&] {
      settings.perturbations.declare_options(table);
      settings.bumps.declare_options(table);
    });
  }
}

// Whether the initial states of `settings` can put a tire on a bump: the tire's reach from
// the base's x, which init_rand_x moves, must end before the first bump's foot (its ramp's,
// if it has one).
std::string bump_start_problem(const EnvSettings& settings) {
  const FloorBumps& bumps = settings.bumps;
  const double tire_radius = RobotModel::default_model()->wheel_radius();
  const double half_footprint = bumps.footprint() / 2.0;
  if (!bumps.enabled() || settings.init_rand.x + tire_radius + half_footprint < bumps.spacing) {
    return "";
  }
  return "init_rand_x (" + shortest_text(settings.init_rand.x) +
         " m) can start the robot on a bump: init_rand_x + the tire radius (" +
         shortest_text(tire_radius) + " m) + bump_width / 2 + bump_ramp x bump_height (" +
         shortest_text(half_footprint) + " m) must be below bump_spacing (" +
         shortest_text(bumps.spacing) + " m)";
}

// The options of the task of `kind`.
void declare_kind_options(Kind kind, EnvSettings& settings, OptionTable& table) {
  switch (kind) {
    case Kind::kServos:
      break;
    case Kind::kPendulum:
      settings.pendulum.declare_options(table);
      break;
    case Kind::kGyropod:
      settings.gyropod.declare_options(table);
      break;
    case Kind::kServosTask:
      settings.task.declare_options(table);
      break;
    case Kind::kVelocity:
      settings.commands.declare_options(table);
      settings.velocity.declare_options(table);
      declare_randomization(table, [&] {
        table.add_real("residual_lag_max", &settings.velocity.residual_lag_max, 0.0, 1.0,
                       "residual mode, training: the agent's action filtered with a time "
                       "constant drawn in U(0, it) per episode [s] in place of residual_filter "
                       "(a regulariser; the base is not lagged)");
      });
      break;
  }
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
  throw std::invalid_argument("environment id \"" + id + "\" not found" +
                              did_you_mean(id, registered_env_ids()) +
                              "; registered ids: " + registered_list() +
                              " (Upkie-PyBullet-* is an alias of Upkie-Bullet-*)");
}

OptionTable env_option_table(const EnvId& id, EnvSettings& settings) {
  set_kind_defaults(id.kind, settings);
  OptionTable table;
  table.add_real("frequency", &settings.frequency, 1.0, 10000.0, "agent rate [Hz]");
  declare_backend_options(id.backend, settings, table);
  declare_randomization(table, [&] {
    table.add_real("observation_noise", &settings.observation_noise, 0.0, kOptionHuge,
                   "uniform noise in +-it on every observation component");
    settings.action_lag.declare_options(table);
  });
  // Part of the task, not a randomisation: it sets the policy's input size, so rollouts,
  // evaluations and the robot's runner carry it from the training options (task_options).
  table.add_integer("observation_history", &settings.observation_history, 1, kMaxObservationHistory,
                    "observations the agent sees: the last k concatenated, newest first "
                    "(\"gyro.y@t-1\" the previous step's), filled with the reset's at reset");
  table.add_integer(kMaxEpisodeStepsOption, &settings.max_episode_steps, 0, 1'000'000'000,
                    "truncate episodes after this many steps, 0 for never");
  declare_randomization(table, [&] { settings.init_rand.declare_options(table); });
  if (id.backend == Backend::kBullet || id.backend == Backend::kMujoco) {
    table.add_rule([&settings] { return bump_start_problem(settings); });
  }
  declare_kind_options(id.kind, settings, table);
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
  // The table checks every option's range and the settings' own rules (pushes, lag,
  // command ranges) once all are read.
  env_option_table(id, settings).apply(options, name);
  return settings;
}

SpineBackendConfig spine_backend_config(const EnvSettings& settings) {
  SpineBackendConfig config = settings.spine;
  config.agent_frequency = settings.frequency;
  config.require_imu_acceleration = settings.velocity.observe_acceleration;
  return config;
}

std::unique_ptr<Env> assemble_env(const EnvId& id, const EnvSettings& settings,
                                  std::unique_ptr<Simulation> simulation,
                                  int physics_steps_per_step) {
  auto servos = std::make_unique<ServosEnv>(std::move(simulation), RobotModel::default_model(),
                                            settings.init_rand, physics_steps_per_step,
                                            settings.perturbations, settings.action_lag);
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
  if (settings.observation_noise > 0.0) {
    env = std::make_unique<ObservationNoise>(std::move(env), settings.observation_noise);
  }
  // After the noise: the history holds the noisy observations the robot's agent would see.
  if (settings.observation_history > 1) {
    env = std::make_unique<ObservationHistory>(std::move(env), settings.observation_history);
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

namespace {

bool names_option(const EnvOptions& options, const std::string& name) {
  return std::any_of(options.begin(), options.end(),
                     [&name](const auto& option) { return option.first == name; });
}

}  // namespace

EnvOptions with_recorded_defaults(const std::string& id, const EnvOptions& recorded) {
  EnvOptions options;
  for (const OptionInfo& info : env_option_info(id)) {
    if (!info.recorded_default.empty() && !names_option(recorded, info.name)) {
      options.emplace_back(info.name, info.recorded_default);
    }
  }
  options.insert(options.end(), recorded.begin(), recorded.end());
  return options;
}

EnvOptions with_pinned_defaults(const std::string& id, const EnvOptions& options) {
  EnvOptions pinned = options;
  for (const OptionInfo& info : env_option_info(id)) {
    if (!info.recorded_default.empty() && !names_option(options, info.name)) {
      pinned.emplace_back(info.name, info.default_value);
    }
  }
  return pinned;
}

std::vector<OptionInfo> env_option_info(const std::string& id) {
  EnvSettings settings;
  return env_option_table(parse_env_id(id), settings).info();
}

}  // namespace upkie_rl
