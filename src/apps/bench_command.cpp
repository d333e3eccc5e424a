/// @file
/// `upkie-rl bench`: environment steps per second of a vector environment.

#include <chrono>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/commands.hpp"
#include "cli/common_flags.hpp"
#include "cli/controller_option.hpp"
#include "cli/option_checks.hpp"
#include "cli/policy_controller.hpp"
#include "envs/controllers/builtin_controllers.hpp"
#include "envs/kinds/servos_env.hpp"
#include "envs/registry/env_factory.hpp"
#include "sim/bullet_simulation.hpp"
#include "vec/make_vector_env.hpp"

namespace upkie_rl::apps {

namespace {

using Clock = std::chrono::steady_clock;

struct BenchOptions {
  std::string env_id;
  std::size_t num_envs = 1;
  int threads = 0;
  int steps = 1000;
  std::string controller = "zero";
  std::vector<std::string> env_options;
  bool raw = false;
  bool json = false;
};

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Steps per second of one BulletSimulation with the neutral servo commands (default
/// settings: 200 Hz, 5 substeps), the reference for the environment layer's overhead.
double raw_simulation_steps_per_s(int steps) {
  auto model = RobotModel::default_model();
  BulletSimulation simulation(model);
  const ServoAction neutral = neutral_servo_action(*model);
  simulation.reset(ResetState{});
  const Clock::time_point start = Clock::now();
  for (int step = 0; step < steps; ++step) simulation.step(neutral);
  return steps / seconds_since(start);
}

void run_bench(const BenchOptions& options) {
  const EnvOptions env_options = parse_env_options(options.env_options);
  std::unique_ptr<Env> probe = make_env(options.env_id, env_options);
  const std::string spec =
      resolve_controller_spec(options.controller, design_env_factory(options.env_id, env_options));
  if (spec != options.controller) std::cout << options.controller << ": " << spec << std::endl;
  std::unique_ptr<Controller> controller = make_builtin_controller(spec, *probe);
  std::unique_ptr<VectorEnv> venv = make_vector_env(options.env_id, env_options, options.num_envs,
                                                    static_cast<std::size_t>(options.threads));
  const std::size_t obs_size = venv->observation_space().size();
  const std::size_t action_size = venv->action_space().size();
  std::vector<float> actions(options.num_envs * action_size);
  const std::span<const float> first = venv->reset(0);
  std::vector<float> observations(first.begin(), first.end());

  const Clock::time_point start = Clock::now();
  for (int step = 0; step < options.steps; ++step) {
    for (std::size_t i = 0; i < options.num_envs; ++i) {
      controller->act(std::span<const float>(observations).subspan(i * obs_size, obs_size),
                      std::span<float>(actions).subspan(i * action_size, action_size));
    }
    const VectorStep& result = venv->step(actions);
    std::copy(result.observations.begin(), result.observations.end(), observations.begin());
  }
  const double elapsed = seconds_since(start);
  const double env_steps_per_s = options.steps * static_cast<double>(options.num_envs) / elapsed;
  const double physics_steps_per_s = env_steps_per_s * probe->physics_steps_per_step();
  const std::size_t threads = std::min(static_cast<std::size_t>(options.threads), options.num_envs);

  std::cout << options.env_id << ": " << options.num_envs << " envs, "
            << (threads == 0 ? std::string("synchronous") : std::to_string(threads) + " threads")
            << ", " << options.steps << " steps in " << elapsed << " s: " << env_steps_per_s
            << " env steps/s, " << physics_steps_per_s << " physics steps/s" << std::endl;
  nlohmann::json summary = {{"env_steps_per_s", env_steps_per_s},
                            {"physics_steps_per_s", physics_steps_per_s},
                            {"num_envs", options.num_envs},
                            {"threads", threads}};
  if (options.raw) {
    const double raw = raw_simulation_steps_per_s(options.steps);
    std::cout << "raw BulletSimulation (neutral commands, default settings): " << raw << " steps/s"
              << std::endl;
    summary["raw_sim_steps_per_s"] = raw;
  }
  if (options.json) std::cout << summary.dump() << std::endl;
}

}  // namespace

void add_bench_command(CLI::App& app) {
  auto options = std::make_shared<BenchOptions>();
  CLI::App* command =
      app.add_subcommand("bench", "Measure environment steps per second of a vector environment");
  add_env_id_option(*command, options->env_id)->required();
  command->add_option("--num-envs", options->num_envs, "Number of environments")
      ->check(finite_range(1, 4096))
      ->capture_default_str();
  add_threads_option(*command, options->threads, "the environments (a pool of this many workers)");
  command->add_option("--steps", options->steps, "Vector steps to time")
      ->check(finite_range(1, 1'000'000'000))
      ->capture_default_str();
  command->add_option("--controller", options->controller, kControllerHelp)->capture_default_str();
  add_env_option_option(*command, options->env_options);
  command->add_flag("--raw", options->raw,
                    "Also time a bare BulletSimulation for the same number of steps");
  add_json_flag(*command, options->json);
  command->callback([options] { run_bench(*options); });
}

}  // namespace upkie_rl::apps
