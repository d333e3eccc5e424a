/// @file
/// `upkie-rl envs`: the registered environment ids with their spaces (and options).

#include <iostream>
#include <memory>
#include <string>

#include "apps/commands.hpp"
#include "envs/kinds/servos_env.hpp"
#include "envs/registry/env_factory.hpp"
#include "envs/registry/registry.hpp"
#include "envs/wrappers/time_limit.hpp"

namespace upkie_rl::apps {

namespace {

/// The Mock environment of the same kind: spaces do not depend on the backend, and this
/// lists Spine ids without a spine running and Bullet ids without building worlds.
std::string mock_twin(const std::string& id) {
  const std::size_t first = id.find('-');
  const std::size_t second = id.find('-', first + 1);
  return id.substr(0, first + 1) + "Mock" + id.substr(second);
}

void print_dict(const char* label, const DictSpace& space) {
  std::cout << "  " << label << " Dict(" << space.entries.size() << " joints), flat Box("
            << space.flat_size() << ")\n";
  for (const auto& [joint, box] : space.entries) {
    std::cout << "      " << joint << ": " << box.describe() << "\n";
  }
}

void list_envs(bool with_options) {
  for (const std::string& id : registered_env_ids()) {
    std::unique_ptr<Env> env = make_env(mock_twin(id));
    Env* inner = env.get();
    if (auto* limit = dynamic_cast<TimeLimit*>(inner)) inner = &limit->inner();
    std::cout << id << "\n";
    if (const auto* servos = dynamic_cast<const ServosEnv*>(inner)) {
      print_dict("observation", servos->observation_dict_space());
      print_dict("action     ", servos->action_dict_space());
    } else {
      std::cout << "  observation " << env->observation_space().describe() << "\n";
      std::cout << "  action      " << env->action_space().describe() << "\n";
    }
    if (with_options) {
      std::cout << "  options:\n";
      for (const std::string& line : env_option_help(id)) std::cout << "      " << line << "\n";
    }
  }
  std::cout << "(Upkie-PyBullet-* is an alias of Upkie-Bullet-*.)" << std::endl;
}

}  // namespace

void add_envs_command(CLI::App& app) {
  auto with_options = std::make_shared<bool>(false);
  CLI::App* command = app.add_subcommand(
      "envs", "List the environment ids with their observation and action spaces");
  command->add_flag("--options", *with_options, "Also list the options each id accepts");
  command->callback([with_options] { list_envs(*with_options); });
}

}  // namespace upkie_rl::apps
