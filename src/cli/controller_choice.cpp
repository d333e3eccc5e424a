#include "cli/controller_choice.hpp"

#include <iostream>

#include "cli/policy_controller.hpp"
#include "envs/controllers/builtin_controllers.hpp"
#include "envs/registry/registry.hpp"

namespace upkie_rl::apps {

EnvOptions run_env_options(const std::string& env_id, const std::string& model,
                           const EnvOptions& given) {
  if (model.empty()) return given;
  EnvOptions options = options_for_model(model, env_id, given);
  if (!options.empty())
    std::cout << "environment options: " << format_env_options(options) << std::endl;
  return options;
}

std::unique_ptr<Controller> make_run_controller(const std::string& env_id,
                                                const std::string& controller,
                                                const std::string& model,
                                                const EnvOptions& env_options, const Env& env) {
  if (!model.empty()) return make_policy_controller(model, env);
  const std::string spec =
      resolve_controller_spec(controller, design_env_factory(env_id, env_options));
  if (spec != controller) std::cout << controller << ": " << spec << std::endl;
  return make_builtin_controller(spec, env);
}

}  // namespace upkie_rl::apps
