#include "apps/policy_controller.hpp"

#include "envs/registry.hpp"

#include "policy/deployed_policy.hpp"

namespace upkie_rl::apps {

namespace {

class PolicyController final : public Controller {
 public:
  explicit PolicyController(DeployedPolicy policy) : policy_(std::move(policy)) {}
  void act(std::span<const float> observation, std::span<float> action) override {
    policy_.act(observation, action);
  }

 private:
  DeployedPolicy policy_;
};

}  // namespace

std::unique_ptr<Controller> make_policy_controller(const std::filesystem::path& model,
                                                   const Env& env) {
  DeployedPolicy policy = DeployedPolicy::load(model);
  try {
    policy.check_spaces(env.observation_space(), env.action_space());
  } catch (const CheckpointError& error) {
    throw CheckpointError("model " + model.string() + " (trained on " + policy.env_id() +
                          ") does not fit this environment: " + error.what());
  }
  return std::make_unique<PolicyController>(std::move(policy));
}

namespace {

constexpr std::string_view kVelocitySuffix = "-Velocity";

/// The pendulum of a velocity task's backend, at the task's rate and physics step: the
/// model its balancer's gains are designed on. Other ids: themselves.
std::pair<std::string, EnvOptions> design_env(const std::string& env_id,
                                              const EnvOptions& nominal) {
  const std::string_view id(env_id);
  if (id.size() <= kVelocitySuffix.size() ||
      id.substr(id.size() - kVelocitySuffix.size()) != kVelocitySuffix) {
    return {env_id, nominal};
  }
  const std::string pendulum =
      std::string(id.substr(0, id.size() - kVelocitySuffix.size())) + "-Pendulum";
  EnvOptions options;
  for (const OptionInfo& info : env_option_info(env_id)) {
    if (info.name == "frequency" || info.name == "nb_substeps") {
      options.emplace_back(info.name, info.default_value);
    }
  }
  for (const auto& [key, value] : task_options(env_id, nominal, pendulum)) {
    options.emplace_back(key, value);  // later keys win: the user's rate and step
  }
  return {pendulum, options};
}

}  // namespace

DesignEnvFactory design_env_factory(const std::string& env_id, const EnvOptions& options) {
  auto [design_id, design_options] = design_env(env_id, task_options(env_id, options, env_id));
  return [design_id, design_options] { return make_env(design_id, design_options); };
}

EnvOptions options_for_model(const std::filesystem::path& model, const std::string& env_id,
                             const EnvOptions& extra) {
  const DeployedPolicy policy = DeployedPolicy::load(model);
  EnvOptions options = task_options(policy.env_id(), policy.env_options(), env_id);
  options.insert(options.end(), extra.begin(), extra.end());
  return options;
}

}  // namespace upkie_rl::apps
