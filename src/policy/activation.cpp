#include "policy/activation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace upkie_rl {

namespace {

struct ActivationNames {
  Activation activation;
  const char* name;         // Ours, in configurations and checkpoint headers.
  const char* torch_name;   // PyTorch's class, as Stable-Baselines3 names it.
  const char* torchscript;  // The aten function TorchScript calls, with default parameters.
};

constexpr std::array<ActivationNames, 9> kActivations{{
    {Activation::kReLU, "relu", "ReLU", "torch.relu"},
    {Activation::kTanh, "tanh", "Tanh", "torch.tanh"},
    {Activation::kELU, "elu", "ELU", "torch.elu"},
    {Activation::kLeakyReLU, "leaky_relu", "LeakyReLU", "torch.leaky_relu"},
    {Activation::kSiLU, "silu", "SiLU", "torch.silu"},
    {Activation::kGELU, "gelu", "GELU", "torch.gelu"},
    {Activation::kSigmoid, "sigmoid", "Sigmoid", "torch.sigmoid"},
    {Activation::kSoftplus, "softplus", "Softplus", "torch.softplus"},
    {Activation::kSELU, "selu", "SELU", "torch.selu"},
}};

double sigmoid(double value) { return 1.0 / (1.0 + std::exp(-value)); }

// Null for a value outside the enumeration (a corrupted cast).
const ActivationNames* names_of(Activation activation) {
  for (const ActivationNames& entry : kActivations) {
    if (entry.activation == activation) return &entry;
  }
  return nullptr;
}

}  // namespace

Activation parse_activation(const std::string& name) {
  for (const ActivationNames& entry : kActivations) {
    if (name == entry.name || name == entry.torch_name) return entry.activation;
  }
  throw std::invalid_argument("unknown activation '" + name + "' (expected " + activation_names() +
                              ")");
}

const char* activation_name(Activation activation) {
  const ActivationNames* names = names_of(activation);
  return names != nullptr ? names->name : "unknown";
}

std::vector<std::pair<std::string, Activation>> activation_spellings() {
  std::vector<std::pair<std::string, Activation>> spellings;
  for (const ActivationNames& entry : kActivations)
    spellings.emplace_back(entry.name, entry.activation);
  for (const ActivationNames& entry : kActivations) {
    spellings.emplace_back(entry.torch_name, entry.activation);
  }
  return spellings;
}

std::vector<Activation> all_activations() {
  std::vector<Activation> activations;
  for (const ActivationNames& entry : kActivations) activations.push_back(entry.activation);
  return activations;
}

std::string activation_names() {
  std::string known;
  for (const ActivationNames& entry : kActivations) {
    known += (known.empty() ? "" : ", ") + std::string(entry.name);
  }
  return known;
}

std::string activation_torchscript(Activation activation, const std::string& x) {
  const ActivationNames* names = names_of(activation);
  if (names == nullptr) throw std::invalid_argument("no TorchScript for an unknown activation");
  return std::string(names->torchscript) + "(" + x + ")";
}

double apply_activation(Activation activation, double value) {
  switch (activation) {
    case Activation::kReLU:
      return std::max(value, 0.0);
    case Activation::kTanh:
      return std::tanh(value);
    case Activation::kELU:
      return value > 0.0 ? value : std::expm1(value);
    case Activation::kLeakyReLU:
      return value > 0.0 ? value : 0.01 * value;
    case Activation::kSiLU:
      return value * sigmoid(value);
    case Activation::kGELU:
      return 0.5 * value * (1.0 + std::erf(value / std::sqrt(2.0)));
    case Activation::kSigmoid:
      return sigmoid(value);
    case Activation::kSoftplus:
      return value > 20.0 ? value : std::log1p(std::exp(value));
    case Activation::kSELU: {
      constexpr double kAlpha = 1.6732632423543772848170429916717;
      constexpr double kScale = 1.0507009873554804934193349852946;
      return kScale * (value > 0.0 ? value : kAlpha * std::expm1(value));
    }
  }
  return value;
}

}  // namespace upkie_rl
