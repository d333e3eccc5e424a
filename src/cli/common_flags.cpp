#include "cli/common_flags.hpp"

#include <algorithm>
#include <iostream>
#include <stdexcept>
#include <thread>

#include "cli/option_checks.hpp"
#include "envs/evaluation/evaluation_start.hpp"
#include "envs/registry/env_settings.hpp"

namespace upkie_rl::apps {

CLI::Option* add_env_id_option(CLI::App& command, std::string& env_id, const std::string& help) {
  const CLI::Validator registered(
      [](std::string& id) {
        try {
          parse_env_id(id);
          return std::string();
        } catch (const std::invalid_argument& error) {
          return std::string(error.what());
        }
      },
      "ID");
  return command.add_option("--env", env_id, help)->check(registered);
}

CLI::Option* add_env_option_option(CLI::App& command, std::vector<std::string>& env_options,
                                   const std::string& scope) {
  return command.add_option("--env-option", env_options,
                            "Environment option key=value" + scope +
                                " (repeatable; `upkie-rl envs --options` lists them)");
}

CLI::Option* add_episodes_option(CLI::App& command, int& episodes, const std::string& scope) {
  return command.add_option("--episodes", episodes, "Number of episodes" + scope)
      ->check(finite_range(1, kMaxEvaluationEpisodes))
      ->capture_default_str();
}

CLI::Option* add_seed_option(CLI::App& command, std::uint64_t& seed, const std::string& of_what,
                             DefaultInHelp default_in_help) {
  CLI::Option* option = command.add_option("--seed", seed, "Seed of " + of_what)->check(kSeed);
  if (default_in_help == DefaultInHelp::kShown) option->capture_default_str();
  return option;
}

CLI::Option* add_threads_option(CLI::App& command, int& threads, const std::string& work) {
  return command
      .add_option("--threads", threads,
                  "Threads that run " + work + "; 0: the calling thread alone, no thread pool")
      ->check(finite_range(0, 1024))
      ->capture_default_str();
}

int one_thread_per_core() {
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

CLI::Option* add_max_steps_option(CLI::App& command, int& max_steps, const std::string& meaning) {
  max_steps = kDefaultMaxSteps;
  return command
      .add_option("--max-steps", max_steps,
                  "End an episode after this many steps (the env's own time limit also "
                  "applies); " +
                      meaning)
      ->check(finite_range(1, 1'000'000'000))
      ->capture_default_str();
}

CLI::Option* add_json_flag(CLI::App& command, bool& json) {
  return command.add_flag("--json", json, "Print the summary as JSON on the last line");
}

CLI::Validator former_spelling_note(const std::string& used, const std::string& current) {
  return CLI::Validator(
      [used, current](std::string&) {
        std::cerr << "upkie-rl: note: " << used << " is now " << current
                  << " (the former spelling still works)" << std::endl;
        return std::string();
      },
      "");
}

}  // namespace upkie_rl::apps
