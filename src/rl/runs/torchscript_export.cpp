#include "rl/runs/torchscript_export.hpp"

#include <torch/script.h>

#include <stdexcept>

#include "base/number_text.hpp"
#include "policy/checkpoint_header.hpp"
#include "policy/provenance.hpp"
#include "rl/runs/ppo_checkpoint.hpp"
#include "rl/runs/run_file_error.hpp"

namespace upkie_rl {

namespace {

std::string literal(double value) {
  std::string text = shortest_text(value);
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

torch::Tensor to_tensor(const std::vector<double>& values) {
  std::vector<float> floats(values.begin(), values.end());
  return torch::tensor(floats, torch::kFloat32);
}

// Builds the module's parameters and the TorchScript source of its forward(): the layers
// of `network`, the activation where it puts it.
std::string add_layers(torch::jit::Module& module, const Mlp& network,
                       const std::vector<DenseLayer>& layers, const std::string& name) {
  std::string source;
  for (std::size_t i = 0; i < layers.size(); ++i) {
    const std::string weight = name + "_" + std::to_string(i) + "_weight";
    const std::string bias = name + "_" + std::to_string(i) + "_bias";
    module.register_parameter(weight, layers[i].weight.detach().clone(), false);
    module.register_parameter(bias, layers[i].bias.detach().clone(), false);
    std::string affine = "torch.matmul(x, self." + weight + ".t()) + self." + bias;
    if (network.activated(i)) affine = activation_torchscript(network.activation(), affine);
    source += "    x = " + affine + "\n";
  }
  return source;
}

}  // namespace

void export_torchscript(const ActorCritic& policy, const ObservationNormalizer& normalizer,
                        const BoxSpace& observation_space, const BoxSpace& action_space,
                        const std::string& env_id, const std::filesystem::path& path,
                        const nlohmann::json& provenance) {
  torch::NoGradGuard no_grad;
  torch::jit::Module module("UpkiePolicy");
  std::string source = "def forward(self, observation: Tensor) -> Tensor:\n";
  source += "    x = observation.float()\n";
  if (normalizer.enabled()) {
    module.register_buffer("observation_mean", to_tensor(normalizer.mean()));
    module.register_buffer("observation_var", to_tensor(normalizer.var()));
    source +=
        "    x = torch.clamp((x - self.observation_mean) / torch.sqrt(self.observation_var + " +
        literal(normalizer.epsilon()) + "), " + literal(-normalizer.clip()) + ", " +
        literal(normalizer.clip()) + ")\n";
  }
  source += add_layers(module, policy.actor_network(), policy.actor_layers(), "actor");
  module.register_buffer("action_low", torch::tensor(action_space.low, torch::kFloat32));
  module.register_buffer("action_high", torch::tensor(action_space.high, torch::kFloat32));
  source += "    return torch.max(torch.min(x, self.action_high), self.action_low)\n";
  module.define(source);

  const nlohmann::json metadata = {
      {provenance_key::kEnvId, env_id},
      {checkpoint_header::kObservationSpace, space_to_json(observation_space)},
      {checkpoint_header::kActionSpace, space_to_json(action_space)},
      {"deterministic", true},
      {checkpoint_header::kProvenance, provenance}};
  torch::jit::ExtraFilesMap extra_files{{"metadata.json", metadata.dump()}};
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  try {
    module.save(path.string(), extra_files);
  } catch (const c10::Error& error) {
    throw RunFileError("cannot write TorchScript model " + path.string() + ": " +
                       error.what_without_backtrace());
  }
}

}  // namespace upkie_rl
