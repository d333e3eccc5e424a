/// @file
/// `upkie-rl spine`: a simulation spine backed by our Bullet or MuJoCo simulation, serving agents
/// (ours through SpineBackend, or the public `upkie` Python environments) over the
/// shared-memory spine link.

#include <spdlog/spdlog.h>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "apps/commands.hpp"
#include "cli/command_error.hpp"
#include "cli/interrupt_handlers.hpp"
#include "cli/live_view.hpp"
#include "cli/option_checks.hpp"
#include "cli/spine_world.hpp"
#include "model/robot_model.hpp"
#include "sim/bullet_simulation.hpp"
#include "sim/mujoco_simulation.hpp"
#include "spine/spine_log_writer.hpp"
#include "spine/spine_server.hpp"

namespace upkie_rl::apps {
namespace {

/// An octal permission mode such as "0660", at most 0666.
unsigned parse_shm_mode(const std::string& text) {
  std::size_t used = 0;
  unsigned long mode = 0;
  try {
    mode = std::stoul(text, &used, 8);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size() || mode > 0666 || (mode & 0600) != 0600) {
    throw std::invalid_argument("--shm-mode: '" + text +
                                "' is not an octal mode between 0600 and 0666");
  }
  return static_cast<unsigned>(mode);
}

/// Largest push of `--push-force`, either way [N] (see add_spine_command).
constexpr double kMaximumPushForce = 500.0;
/// Latest start and longest duration of a push [s]: a simulated day, longer than any
/// episode; only bounded so that no setting is unbounded.
constexpr double kMaximumPushSeconds = 86400.0;

struct SpineOptions {
  std::string shm_name = "/upkie";
  std::string shm_mode = "0600";
  double spine_frequency = 1000.0;
  int nb_substeps = 0;
  std::string backend = "bullet";
  /// A push in every episode: force [N] along the world's x axis (forward) on the base,
  /// from `push_time` to push_time + push_duration after each Start [s]. 0 N: none.
  double push_force = 0.0;
  double push_time = 1.0;
  double push_duration = 0.2;
  double observation_latency = 0.0;  ///< Age of the observations sent [s].
  double cycle_jitter = 0.0;         ///< Lateness of each cycle, up to [s].
  double action_delay = 0.0;         ///< Age of the commands applied [s].
  double action_lag = 0.0;           ///< First-order lag of the commands applied [s].
  /// The hidden world: perturbation options ("NAME=VALUE") of the environments.
  std::vector<std::string> physics_options;
  LiveViewOptions view;
  /// Write every simulation step to this spine log (mpacklog), empty for none.
  std::string log_path;
};

/// Writes the spine log of `--log`: each step's cycle as Upkie's spines log it, the
/// observation the agent saw before the step with the commands applied in it (so an episode's
/// last observation is not written). Reports a write error once, then stops writing.
class SpineStepLogger {
 public:
  explicit SpineStepLogger(const std::string& path) : writer_(path) {}
  void observe(const Observation& observation, const ServoAction& action, bool reset) {
    if (failed_) return;
    try {
      if (!reset && has_previous_) writer_.write(previous_, action);
    } catch (const std::exception& error) {
      spdlog::error("spine log: {}", error.what());
      failed_ = true;
    }
    previous_ = observation;
    has_previous_ = true;
  }
  void close() { writer_.close(); }

 private:
  SpineLogWriter writer_;
  Observation previous_;
  bool has_previous_ = false;
  bool failed_ = false;
};

/// Applies the push of `options` to `simulation` at the simulation time of `observation`.
void apply_push(const SpineOptions& options, PhysicsSimulation& simulation,
                const Observation& observation) {
  if (options.push_force == 0.0) return;
  const double since = observation.time - options.push_time;
  const bool pushing = since >= 0.0 && since < options.push_duration;
  const Eigen::Vector3d force(pushing ? options.push_force : 0.0, 0.0, 0.0);
  if (force != simulation.base_force()) simulation.set_base_force(force);
}

/// Streams every simulation step of the spine to a LiveView: each Start begins an episode,
/// and the "actions" plotted are the six servo velocity targets.
std::unique_ptr<LiveView> view_spine(const SpineOptions& options, SpineServer& server,
                                     double timestep) {
  std::vector<std::string> action_names;
  for (const auto& joint : kServoNames) action_names.push_back(std::string(joint) + ".velocity");
  auto view = std::make_unique<LiveView>(options.view,
                                         "spine " + options.shm_name + " (" + options.backend + ")",
                                         timestep, action_names);
  server.set_simulation_observer(
      [viewer = view.get(), episode = -1, step = 0, velocities = std::array<float, kNumServos>{}](
          const Observation& observation, const ServoAction& action, bool reset) mutable {
        if (reset) {
          viewer->start_episode(++episode);
          step = 0;
        } else {
          ++step;
        }
        for (std::size_t i = 0; i < kNumServos; ++i) {
          velocities[i] = static_cast<float>(action[i].velocity);
        }
        viewer->publish(observation, step, 0.0, velocities);
      });
  return view;
}

/// The physics backend the spine serves.
std::unique_ptr<PhysicsSimulation> make_physics(const std::string& backend,
                                                std::shared_ptr<const RobotModel> model,
                                                const PhysicsConfig& physics) {
  if (backend == "mujoco") {
    MujocoConfig config;
    static_cast<PhysicsConfig&>(config) = physics;
    return std::make_unique<MujocoSimulation>(std::move(model), config);
  }
  BulletConfig config;
  static_cast<PhysicsConfig&>(config) = physics;
  return std::make_unique<BulletSimulation>(std::move(model), config);
}

/// The server's settings: shared memory, pacing, latency and the model's torque limits.
SpineServerConfig spine_config(const SpineOptions& options, const PhysicsSimulation& simulation,
                               const PhysicsConfig& physics, const RobotModel& model) {
  SpineServerConfig config;
  config.shm_name = options.shm_name;
  config.shm_mode = parse_shm_mode(options.shm_mode);
  config.real_time = options.nb_substeps == 0;
  config.frequency = options.spine_frequency;
  config.default_servo_gains = simulation.servo_gains();
  // In simulation steps: one per cycle in real time, one per action on request.
  const double step_duration = physics.physics_timestep * physics.nb_substeps;
  config.observation_delay_steps =
      static_cast<int>(std::lround(options.observation_latency / step_duration));
  config.actuation.delay_steps =
      static_cast<int>(std::lround(options.action_delay / step_duration));
  config.actuation.time_constant = options.action_lag;
  config.actuation.step_duration = step_duration;
  config.cycle_jitter = options.cycle_jitter;
  for (std::size_t i = 0; i < kNumServos; ++i) {
    config.maximum_torques[i] = model.servo_limits(i).effort;
  }
  return config;
}

/// What the spine serves, and how, in the log.
void log_spine_start(const SpineOptions& options, const PhysicsConfig& physics,
                     const SpineServerConfig& config, const SpineWorld& world) {
  if (config.real_time) {
    spdlog::info("spine {}: {}, real time, {} Hz, one {} s physics step per cycle",
                 options.shm_name, options.backend, options.spine_frequency,
                 physics.physics_timestep);
  } else {
    spdlog::info("spine {}: {}, on request, {} physics steps of {} s per action", options.shm_name,
                 options.backend, physics.nb_substeps, physics.physics_timestep);
  }
  if (config.observation_delay_steps > 0 || config.cycle_jitter > 0.0) {
    spdlog::info("spine {}: observations {} simulation steps old, cycles up to {} ms late",
                 options.shm_name, config.observation_delay_steps, 1e3 * config.cycle_jitter);
  }
  if (config.actuation.any()) {
    spdlog::info("spine {}: commands applied {} simulation steps late, lag {} s", options.shm_name,
                 config.actuation.delay_steps, config.actuation.time_constant);
  }
  if (world.any()) spdlog::info("spine {}: physics {}", options.shm_name, world.describe());
}

void run_spine(const SpineOptions& options) {
  if (!(options.spine_frequency > 0.0)) {
    throw std::invalid_argument("--spine-frequency must be positive");
  }
  if (options.push_force != 0.0 && options.view.enabled) {
    throw std::invalid_argument("--push-force does not work with --view yet");
  }
  if (!options.log_path.empty() && options.view.enabled) {
    throw std::invalid_argument("--log does not work with --view yet");
  }
  const bool real_time = options.nb_substeps == 0;
  std::shared_ptr<const RobotModel> model = RobotModel::default_model();

  // One physics step per cycle in real time; K physics steps per Action otherwise.
  PhysicsConfig physics;
  physics.physics_timestep = 1.0 / options.spine_frequency;
  physics.nb_substeps = real_time ? 1 : options.nb_substeps;
  const std::unique_ptr<PhysicsSimulation> engine = make_physics(options.backend, model, physics);
  PhysicsSimulation& simulation = *engine;

  const SpineServerConfig config = spine_config(options, simulation, physics, *model);
  const SpineWorld world(options.physics_options);

  std::unique_ptr<SpineStepLogger> logger;
  if (!options.log_path.empty()) logger = std::make_unique<SpineStepLogger>(options.log_path);
  std::string error;
  {
    InterruptHandlers handlers;
    SpineServer server(
        simulation, config, [&simulation] { simulation.step_braked(); },
        [&simulation, &world,
         starts = std::uint64_t{0}](const SpineStartSettings& settings) mutable {
          simulation.set_servo_gains(settings.servo_gains);
          simulation.set_variation(world.episode_variation(starts++, settings.imu_uncertainty));
        });
    std::unique_ptr<LiveView> view;
    if (options.view.enabled) {
      view = view_spine(options, server, physics.physics_timestep * physics.nb_substeps);
      view->wait_for_browsers();
    } else if (options.push_force != 0.0 || logger) {
      server.set_simulation_observer(
          [&options, &simulation, &logger](const Observation& observation,
                                           const ServoAction& action, bool reset) {
            apply_push(options, simulation, observation);
            if (logger) logger->observe(observation, action, reset);
          });
    }
    log_spine_start(options, physics, config, world);
    server.run(interrupt_requested);
    error = server.error();
    if (view) view->end(error.empty() ? "the spine is over" : "the spine shut down: " + error);
    spdlog::info("spine {}: over after {} cycles, {} simulation steps", options.shm_name,
                 server.nb_cycles(), server.nb_simulation_steps());
  }  // the shared memory is unlinked here
  if (logger) logger->close();
  if (!error.empty()) throw CommandError("spine shut down: " + error);
}

/// The spine's hidden reality: actuation timing and the world's physics.
void add_reality_options(CLI::App& command, SpineOptions& options) {
  command
      .add_option("--action-delay", options.action_delay,
                  "Sim-to-real actuation: apply the agent's commands this late [s], rounded to "
                  "simulation steps (hidden from the agent; logs show the commands as sent)")
      ->capture_default_str()
      ->check(finite_range(0.0, 1.0));
  command
      .add_option("--action-lag", options.action_lag,
                  "Sim-to-real actuation: the servos' targets follow the commands with this "
                  "first-order time constant [s]")
      ->capture_default_str()
      ->check(finite_range(0.0, 10.0));
  command.add_option("--physics-option", options.physics_options,
                     "NAME=VALUE, repeatable: a perturbation option of the environments "
                     "(mass_scale, payload_mass, payload_offset_x, floor_friction, "
                     "torque_limit_scale, slope_pitch, ...; `upkie-rl envs --options`), the "
                     "world this spine plays without telling its agents");
}

}  // namespace

void add_spine_command(CLI::App& app) {
  auto options = std::make_shared<SpineOptions>();
  CLI::App* command = app.add_subcommand(
      "spine",
      "Run a simulation spine: Bullet or MuJoCo served over shared memory to an agent "
      "(SpineBackend, "
      "or the upkie Python package). Ctrl-C stops it and removes the shared memory.");
  command->add_option("--shm-name", options->shm_name, "Shared-memory name")->capture_default_str();
  command
      ->add_option("--shm-mode", options->shm_mode,
                   "Permissions of the shared memory, octal: 0600 lets only this user's agents "
                   "drive the robot; 0660 adds the group, 0666 everyone")
      ->capture_default_str();
  command
      ->add_option("--spine-frequency", options->spine_frequency,
                   "Cycles per second in real time, and 1/physics timestep [Hz]")
      ->capture_default_str()
      ->check(finite_range(1.0, 100000.0));
  command
      ->add_option("--nb-substeps", options->nb_substeps,
                   "0: real-time loop; K > 0: advance only on actions, K physics steps each")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  command->add_option("--backend", options->backend, "Physics engine")
      ->capture_default_str()
      ->check(CLI::IsMember({"bullet", "mujoco"}));
  // Upkie weighs 5.3 kg: 500 N (as `drive --push-force`) is about ten times its weight,
  // beyond any push a balancer survives; larger forces only test how the physics engine
  // diverges.
  command
      ->add_option("--push-force", options->push_force,
                   "Push the base forward (negative: backward) with this force in every "
                   "episode [N], 0 for none")
      ->capture_default_str()
      ->check(finite_range(-kMaximumPushForce, kMaximumPushForce));
  command->add_option("--push-time", options->push_time, "When the push starts after a Start [s]")
      ->capture_default_str()
      ->check(finite_range(0.0, kMaximumPushSeconds));
  command->add_option("--push-duration", options->push_duration, "How long the push lasts [s]")
      ->capture_default_str()
      ->check(finite_range(0.0, kMaximumPushSeconds));
  command
      ->add_option("--observation-latency", options->observation_latency,
                   "Sim-to-real timing: send observations this old [s], rounded to simulation "
                   "steps (the pi3hat's are about one 1 ms cycle old)")
      ->capture_default_str()
      ->check(finite_range(0.0, 10.0));
  command
      ->add_option("--cycle-jitter", options->cycle_jitter,
                   "Sim-to-real timing, real time: start each cycle up to this late [s]")
      ->capture_default_str()
      ->check(finite_range(0.0, 1.0));
  add_reality_options(*command, *options);
  command
      ->add_option("--log", options->log_path,
                   "Write every simulation step to this spine log (mpacklog: a stream of "
                   "MessagePack dictionaries, as Upkie's spines write; `upkie-rl identify` and "
                   "Python's mpacklog read it)")
      ->check(kNonEmptyPath);
  options->view.speed = 0.0;  // the spine keeps its own pace
  add_live_view_options(*command, options->view, false);
  command->callback([options] { run_spine(*options); });
}

}  // namespace upkie_rl::apps
