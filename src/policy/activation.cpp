#include "policy/activation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace upkie_rl {

namespace {

struct ActivationNames {
  Activation activation;
  const char* name;        // Ours, in configurations and checkpoint headers.
  const char* torch_name;  // PyTorch's class, as Stable-Baselines3 names it.
};

constexpr std::array<ActivationNames, 9> kActivations{{
    {Activation::kReLU, "relu", "ReLU"},
    {Activation::kTanh, "tanh", "Tanh"},
    {Activation::kELU, "elu", "ELU"},
    {Activation::kLeakyReLU, "leaky_relu", "LeakyReLU"},
    {Activation::kSiLU, "silu", "SiLU"},
    {Activation::kGELU, "gelu", "GELU"},
    {Activation::kSigmoid, "sigmoid", "Sigmoid"},
    {Activation::kSoftplus, "softplus", "Softplus"},
    {Activation::kSELU, "selu", "SELU"},
}};

double sigmoid(double value) { return 1.0 / (1.0 + std::exp(-value)); }

}  // namespace

Activation parse_activation(const std::string& name) {
  std::string known;
  for (const ActivationNames& entry : kActivations) {
    if (name == entry.name || name == entry.torch_name) return entry.activation;
    known += (known.empty() ? "" : ", ") + std::string(entry.name);
  }
  throw std::invalid_argument("unknown activation '" + name + "' (expected " + known + ")");
}

const char* activation_name(Activation activation) {
  for (const ActivationNames& entry : kActivations) {
    if (entry.activation == activation) return entry.name;
  }
  return "unknown";
}

bool is_trainable(Activation activation) {
  return activation == Activation::kReLU || activation == Activation::kTanh;
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
