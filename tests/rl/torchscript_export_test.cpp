#include "rl/runs/torchscript_export.hpp"

#include <gtest/gtest.h>
#include <torch/script.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>

namespace upkie_rl {
namespace {

constexpr const char* kSystemPython = "/usr/bin/python3";

struct Exported {
  std::filesystem::path directory;
  std::filesystem::path model;
  torch::Tensor inputs;
  torch::Tensor expected;
};

// Exports a small policy with normalisation and bounded actions, and computes the expected
// actions with our own C++ code (normaliser + differentiable forward + clamp).
Exported export_policy(Activation activation = Activation::kReLU) {
  Exported out;
  out.directory = std::filesystem::temp_directory_path() /
                  ("upkie_rl_torchscript_" + std::to_string(::getpid()));
  std::filesystem::create_directories(out.directory);
  out.model = out.directory / "policy.pt";
  PolicyConfig config;
  config.actor_hidden_sizes = {16, 16};
  config.critic_hidden_sizes = {16};
  config.activation = activation;
  ActorCritic policy(3, 2, config, 4);
  {
    torch::NoGradGuard no_grad;
    policy.flat_parameters().add_(torch::randn_like(policy.flat_parameters()) * 0.3);
  }
  const nlohmann::json state = {
      {"observations", {{"mean", {0.1, -0.2, 0.3}}, {"var", {2.0, 0.5, 1.0}}, {"count", 5.0}}},
      {"config", {{"observations", true}, {"clip_observations", 5.0}, {"epsilon", 1e-8}}}};
  const ObservationNormalizer normalizer = ObservationNormalizer::from_state(state, 3);
  BoxSpace observation_space{{-1, -1, -1}, {1, 1, 1}, {"a", "b", "c"}};
  BoxSpace action_space{{-0.5f, -1.0f}, {0.5f, 1.0f}, {"u", "v"}};
  export_torchscript(policy, normalizer, observation_space, action_space, "Test-Env", out.model);

  out.inputs = torch::randn({5, 3}) * 3.0;
  std::vector<float> normalized(15);
  normalizer.normalize({out.inputs.data_ptr<float>(), 15}, normalized);
  torch::NoGradGuard no_grad;
  const torch::Tensor mean =
      policy.action_mean(torch::from_blob(normalized.data(), {5, 3}).clone());
  out.expected =
      torch::max(torch::min(mean, torch::tensor({0.5f, 1.0f})), torch::tensor({-0.5f, -1.0f}));
  return out;
}

nlohmann::json to_json(const torch::Tensor& tensor) {
  nlohmann::json rows = nlohmann::json::array();
  for (std::int64_t i = 0; i < tensor.size(0); ++i) {
    std::vector<float> row(tensor[i].data_ptr<float>(),
                           tensor[i].data_ptr<float>() + tensor.size(1));
    rows.push_back(row);
  }
  return rows;
}

TEST(TorchScriptExport, LoadsBackInCppWithTheSameActions) {
  for (const Activation activation : all_activations()) {
    SCOPED_TRACE(activation_name(activation));
    const Exported exported = export_policy(activation);
    torch::jit::Module module = torch::jit::load(exported.model.string());
    const torch::Tensor actions = module.forward({exported.inputs}).toTensor();
    EXPECT_TRUE(torch::allclose(actions, exported.expected, 1e-5, 1e-6));
    std::filesystem::remove_all(exported.directory);
  }
}

TEST(TorchScriptExport, LoadsInPythonWithTorchJitLoad) {
  if (access(kSystemPython, X_OK) != 0) GTEST_SKIP() << kSystemPython << " not found";
  if (std::system((std::string(kSystemPython) + " -c 'import torch' 2>/dev/null").c_str()) != 0) {
    GTEST_SKIP() << "python3-torch is not installed";
  }
  const Exported exported = export_policy();
  const std::filesystem::path case_path = exported.directory / "case.json";
  std::ofstream(case_path) << nlohmann::json{{"model", exported.model.string()},
                                             {"env_id", "Test-Env"},
                                             {"inputs", to_json(exported.inputs)},
                                             {"expected", to_json(exported.expected)}}
                                  .dump();
  const std::string script =
      std::string(UPKIE_RL_SOURCE_DIR) + "/python/tests/test_torchscript_export.py";
  const int status =
      std::system((std::string(kSystemPython) + " " + script + " " + case_path.string()).c_str());
  EXPECT_EQ(status, 0) << "the Python check failed; see its output above";
  std::filesystem::remove_all(exported.directory);
}

}  // namespace
}  // namespace upkie_rl
