#include "cli/policy_controller.hpp"

#include "envs/registry/registry.hpp"

#include "envs/registry/env_factory.hpp"
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

DesignEnvFactory design_env_factory(const std::string& env_id, const EnvOptions& options) {
  // The task's options without the randomisation: controllers are designed in nominal
  // conditions (the velocity balancer on the velocity task itself).
  EnvOptions design_options = task_options(env_id, options, env_id);
  return [env_id, design_options] { return make_env(env_id, design_options); };
}

EnvOptions options_for_model(const std::filesystem::path& model, const std::string& env_id,
                             const EnvOptions& extra) {
  const DeployedPolicy policy = DeployedPolicy::load(model);
  EnvOptions options = task_options(policy.env_id(), policy.env_options(), env_id);
  options.insert(options.end(), extra.begin(), extra.end());
  return options;
}

}  // namespace upkie_rl::apps
