#include "envs/registry/env_factory.hpp"

/// @file
/// make_env and make_env_factory (envs/registry/env_factory.hpp): the backends of each id, physics
/// engines included. The engine-bound half of the registry; the rest (ids, options, the
/// task chain) is engine-free in registry.cpp.

#include <algorithm>
#include <cmath>

#include "envs/registry/env_settings.hpp"
#include "envs/registry/registry.hpp"
#include "sim/bullet_simulation.hpp"
#include "sim/mock_simulation.hpp"
#include "sim/mujoco_simulation.hpp"

namespace upkie_rl {
namespace {

/// The physics settings of `settings`, common to Bullet and MuJoCo: rates, inertias and
/// the world's bumps.
void set_physics(const EnvSettings& settings, PhysicsConfig& config) {
  config.nb_substeps =
      settings.nb_substeps > 0
          ? settings.nb_substeps
          : std::max(1, static_cast<int>(std::lround(1000.0 / settings.frequency)));
  config.physics_timestep = 1.0 / (settings.frequency * config.nb_substeps);
  config.inertia_source = settings.inertia_source;
  config.bumps = settings.bumps;
}

/// The robot's MuJoCo physics (tires, wheel damping: MujocoConfig's defaults, the same for
/// every task and for the simulation spine) at the rate of `settings`.
MujocoConfig mujoco_config(const EnvSettings& settings) {
  MujocoConfig config;
  set_physics(settings, config);
  return config;
}

/// `mujoco_model`: MuJoCo's compiled model, built once per factory and shared by its
/// environments (null for the other backends).
std::unique_ptr<Simulation> make_simulation(const EnvId& id, const EnvSettings& settings,
                                            const std::shared_ptr<const MujocoModel>& mujoco_model,
                                            int& physics_steps_per_step) {
  const std::shared_ptr<const RobotModel> model = RobotModel::default_model();
  switch (id.backend) {
    case EnvBackend::kBullet: {
      BulletConfig config;
      set_physics(settings, config);
      physics_steps_per_step = config.nb_substeps;
      return std::make_unique<BulletSimulation>(model, config);
    }
    case EnvBackend::kMujoco: {
      const MujocoConfig config = mujoco_config(settings);
      physics_steps_per_step = config.nb_substeps;
      return std::make_unique<MujocoSimulation>(model, config, mujoco_model);
    }
    case EnvBackend::kSpine:
      physics_steps_per_step = 0;
      return std::make_unique<SpineBackend>(spine_backend_config(settings));
    case EnvBackend::kMock:
    default:
      physics_steps_per_step = 0;
      return std::make_unique<MockSimulation>(model, 1.0 / settings.frequency);
  }
}

}  // namespace

EnvFactory make_env_factory(const std::string& id, const EnvOptions& options) {
  const EnvId parsed = parse_env_id(id);
  const EnvSettings settings = parse_env_settings(parsed, id, options);
  // Fail here, not in the factory, on the model or a settings error.
  const std::shared_ptr<const RobotModel> model = RobotModel::default_model();
  std::shared_ptr<const MujocoModel> mujoco_model;
  if (parsed.backend == EnvBackend::kMujoco) {
    const MujocoConfig config = mujoco_config(settings);
    config.validate();
    mujoco_model = build_mujoco_model(*model, config);
  }
  return [parsed, settings, mujoco_model]() {
    int physics_steps_per_step = 0;
    std::unique_ptr<Simulation> simulation =
        make_simulation(parsed, settings, mujoco_model, physics_steps_per_step);
    return assemble_env(parsed, settings, std::move(simulation), physics_steps_per_step);
  };
}

std::unique_ptr<Env> make_env(const std::string& id, const EnvOptions& options) {
  return make_env_factory(id, options)();
}

}  // namespace upkie_rl
