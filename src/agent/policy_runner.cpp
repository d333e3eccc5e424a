#include "agent/policy_runner.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <memory>
#include <optional>
#include <vector>

#include "agent/agent_error.hpp"
#include "agent/flight_recorder.hpp"
#include "agent/loop_monitor.hpp"
#include "agent/supervised_spine.hpp"
#include "agent/supervisor.hpp"
#include "agent/velocity_commander.hpp"
#include "envs/kinds/velocity_env.hpp"
#include "envs/registry/env_settings.hpp"
#include "envs/registry/registry.hpp"
#include "policy/deployed_policy.hpp"

namespace upkie_rl {
namespace {

using Clock = std::chrono::steady_clock;

/// The environment a policy runs in: its task on the spine backend, with the training
/// options that define the task (envs/registry/registry.hpp task_options), no time limit.
struct RobotEnv {
  std::unique_ptr<Supervisor> supervisor;  // Outlives env, whose link refers to it.
  std::unique_ptr<Env> env;
  SupervisedSpine* link = nullptr;               // Owned by env.
  double frequency = 0.0;                        // [Hz]
  std::unique_ptr<VelocityCommander> commander;  // Velocity tasks only; refers to env.
};

/// The velocity task's command input, made (a file read, a terminal set up) before the spine
/// is touched; refused for other tasks.
std::unique_ptr<VelocityCommandInput> make_task_command_input(const EnvId& trained,
                                                              const DeployedPolicy& policy,
                                                              const RunnerOptions& options) {
  if (trained.kind == EnvKind::kVelocity) return make_command_input(options);
  if (!options.commands.empty() || options.keyboard) {
    throw AgentError("--commands and --keyboard need a velocity policy (Upkie-*-Velocity); " +
                     options.model.string() + " was trained on " + policy.env_id());
  }
  return nullptr;
}

RobotEnv make_robot_env(const DeployedPolicy& policy, const RunnerOptions& options,
                        const std::atomic<bool>& interrupt) {
  const EnvId trained = parse_env_id(policy.env_id());
  const EnvId robot{EnvBackend::kSpine, trained.kind};
  const std::string name = env_id_name(robot.backend, robot.kind);
  EnvOptions env_options = task_options(policy.env_id(), policy.env_options(), name);
  env_options.emplace_back("shm_name", options.shm_name);
  env_options.emplace_back(kMaxEpisodeStepsOption, "0");
  env_options.emplace_back("request_timeout", std::to_string(options.limits.spine_timeout));
  env_options.emplace_back("open_tries", std::to_string(options.open_tries));
  std::unique_ptr<VelocityCommandInput> commands =
      make_task_command_input(trained, policy, options);
  const EnvSettings settings = parse_env_settings(robot, name, env_options);
  RobotEnv robot_env;
  robot_env.supervisor = std::make_unique<Supervisor>(options.limits, RobotModel::default_model(),
                                                      1.0 / settings.frequency);
  SpineBackendConfig spine_config = spine_backend_config(settings);
  spine_config.open_interrupt = &interrupt;  // Ctrl-C ends the wait for the spine at once
  auto spine = std::make_unique<SpineBackend>(spine_config);
  auto link =
      std::make_unique<SupervisedSpine>(std::move(spine), *robot_env.supervisor, options.dry_run);
  robot_env.link = link.get();
  robot_env.frequency = settings.frequency;
  robot_env.env = assemble_env(robot, settings, std::move(link), 0);
  policy.check_spaces(robot_env.env->observation_space(), robot_env.env->action_space());
  if (VelocityEnv* velocity = find_velocity_env(*robot_env.env)) {
    // The ranges of the training's commands, randomisation options included.
    const VelocityCommandRanges trained_ranges =
        parse_env_settings(trained, policy.env_id(), policy.env_options()).commands;
    robot_env.commander =
        std::make_unique<VelocityCommander>(*velocity, std::move(commands), trained_ranges);
  }
  spdlog::info("policy {} ({}), on {} at {} Hz", options.model.string(), policy.env_id(), name,
               settings.frequency);
  return robot_env;
}

/// Logs, about once a second, the commands a dry run does not send.
void log_dry_run(const SupervisedSpine& link, int cycle, double frequency) {
  if (cycle % std::max(1, static_cast<int>(frequency)) != 0) return;
  const ServoAction& action = link.intended_action();
  std::string text;
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    const ServoCommand& command = action[servo];
    text +=
        fmt::format(" {}: position {:.4f} velocity {:.4f} max_torque {:.2f};", kServoNames[servo],
                    command.position, command.velocity, command.maximum_torque);
  }
  spdlog::info("dry run, cycle {}, not sent:{}", cycle, text);
}

/// The running state's loop; returns why it ended normally (duration, interrupt).
/// @throws SupervisorTrip, SpineError, and the other errors of a cycle.
std::string run_loop(DeployedPolicy& policy, RobotEnv& robot, Supervisor& supervisor,
                     const RunnerOptions& options, const std::atomic<bool>& interrupt,
                     LoopMonitor& monitor, std::optional<FlightRecorder>& recorder,
                     std::span<float> observation) {
  Env& env = *robot.env;
  std::vector<float> action(env.action_space().size());
  const auto start = Clock::now();
  monitor.on_cycle_start(start);
  for (int cycle = 0;; ++cycle) {
    if (interrupt.load(std::memory_order_relaxed)) return "interrupted (SIGINT or SIGTERM)";
    const auto cycle_start = Clock::now();
    if (options.duration > 0.0 &&
        std::chrono::duration<double>(cycle_start - start).count() >= options.duration) {
      return "duration of " + fmt::format("{}", options.duration) + " s reached";
    }
    policy.act(observation, action);
    const double policy_time = std::chrono::duration<double>(Clock::now() - cycle_start).count();
    supervisor.check_policy_output(action, env.action_space());
    if (recorder) recorder->before_step(env, observation);
    if (robot.commander) robot.commander->update((cycle + 1) / robot.frequency);
    const StepResult result = env.step(action, observation);
    if (options.dry_run) log_dry_run(*robot.link, cycle, robot.frequency);
    monitor.on_cycle_start(Clock::now());
    if (recorder) {
      recorder->after_step(cycle, action, result, supervisor.state(), monitor.last_period(),
                           policy_time, monitor.last_missed());
    }
    if (result.terminated) {
      throw SupervisorTrip(
          "task termination: the training environment's end condition "
          "(fall, drift or speed bound)");
    }
  }
}

/// Sends what a spine expects of a stopping agent, filling the summary's stop fields. Before
/// the environment exists (a bad checkpoint), only the Stop request, if a spine is there.
/// `cut_short`: as SupervisedSpine::send_stop_commands.
void send_stop_commands(RobotEnv& robot, const RunnerOptions& options,
                        const std::atomic<bool>& cut_short, RunSummary& summary) {
  if (robot.link != nullptr && robot.supervisor->state() != SupervisorState::kIdle) {
    const int planned = options.limits.nb_stop_cycles;
    summary.stop_cycles_sent = robot.link->send_stop_commands(planned, cut_short);
    summary.stop_cut_short = summary.stop_cycles_sent < planned && cut_short.load();
    spdlog::info("stopping: {} of {} stop cycles answered{}, Stop request sent",
                 summary.stop_cycles_sent, planned,
                 summary.stop_cut_short ? " (cut short by SIGINT or SIGTERM)" : "");
    return;
  }
  try {
    SpineBackendConfig config;
    config.shm_name = options.shm_name;
    config.open_tries = 1;
    config.request_timeout = options.limits.spine_timeout;
    SpineBackend spine(config);
    spine.force_stop();
    spdlog::info("stopping: nothing was started; Stop request sent to the spine {}",
                 options.shm_name);
  } catch (const std::exception& error) {
    spdlog::info("stopping: nothing was started, and no spine to stop ({})", error.what());
  }
}

/// Goes to `next` on the supervisor if there is one, else logs the same line.
void transition(const RobotEnv& robot, SupervisorState from, SupervisorState next,
                const std::string& reason) {
  if (robot.supervisor) {
    robot.supervisor->transition(next, reason);
  } else {
    spdlog::info("supervisor: {} -> {}: {}", supervisor_state_name(from),
                 supervisor_state_name(next), reason);
  }
}

}  // namespace

RunSummary run_policy(const RunnerOptions& options, std::atomic<bool>& interrupt) {
  RunSummary summary;
  std::optional<LoopMonitor> monitor;
  RobotEnv robot;
  std::optional<FlightRecorder> recorder;
  try {
    options.limits.validate();
    DeployedPolicy policy = DeployedPolicy::load(options.model);
    robot = make_robot_env(policy, options, interrupt);
    if (!options.record.empty()) {
      recorder.emplace(options.record);
      recorder->write_header(*robot.env);
    }
    monitor.emplace(1.0 / robot.frequency, options.limits.max_consecutive_deadline_misses,
                    options.limits.max_cycle_periods);
    robot.supervisor->transition(
        SupervisorState::kStarting,
        "starting the spine " + options.shm_name +
            (options.dry_run ? " (dry run: only stop commands are sent)" : ""));
    std::vector<float> observation(robot.env->observation_space().size());
    if (robot.commander) robot.commander->start();
    robot.env->reset(0, observation);
    robot.supervisor->transition(SupervisorState::kRunning, "first observation within limits");
    summary.stop_reason = run_loop(policy, robot, *robot.supervisor, options, interrupt, *monitor,
                                   recorder, observation);
    summary.completed = true;
  } catch (const std::exception& error) {
    summary.stop_reason = error.what();
  }
  interrupt.store(false);  // The one that caused the stop; a second one cuts stopping short.
  transition(robot, SupervisorState::kIdle, SupervisorState::kStopping, summary.stop_reason);
  send_stop_commands(robot, options, interrupt, summary);
  if (recorder) {
    try {
      recorder->close();
    } catch (const std::exception& error) {
      spdlog::error("{}", error.what());
    }
  }
  if (monitor) summary.loop = monitor->statistics();
  std::unique_ptr<Supervisor> supervisor = std::move(robot.supervisor);
  robot = RobotEnv{};  // Detaches from the spine.
  robot.supervisor = std::move(supervisor);
  transition(robot, SupervisorState::kStopping, SupervisorState::kStopped,
             "detached from the spine");
  return summary;
}

}  // namespace upkie_rl
