#pragma once
/// @file
/// Activation of the hidden layers of the policy and value networks: the one list of
/// activations, with their names, scalar definitions and TorchScript spellings, shared by
/// training (rl/ppo/tensor_activation.hpp applies them to tensors), deployment
/// (policy/deployed_policy.hpp), and export (rl/runs/torchscript_export.hpp, onnx/).

#include <string>
#include <utility>
#include <vector>

namespace upkie_rl {

/// PyTorch's definitions with its default parameters (Stable-Baselines3 policies use them).
/// The trainer trains every one: with the hand-written gradient for those it covers
/// (rl/ppo/ppo_gradient.hpp, ReLU and Tanh), with autograd for the others (`ppo.gradient`).
enum class Activation {
  kReLU,
  kTanh,
  kELU,        ///< x if x > 0 else eˣ − 1 (α = 1).
  kLeakyReLU,  ///< x if x > 0 else 0.01·x.
  kSiLU,       ///< x·σ(x).
  kGELU,       ///< x·Φ(x), exact (erf), as torch.nn.GELU().
  kSigmoid,    ///< σ(x) = 1/(1 + e⁻ˣ).
  kSoftplus,   ///< log(1 + eˣ), x itself above 20 (torch's threshold).
  kSELU,       ///< λ·(x if x > 0 else α·(eˣ − 1)), λ ≈ 1.0507, α ≈ 1.6733.
};

/// Parses an activation name, lower case ("relu", "leaky_relu", ...) or PyTorch's class name
/// ("ReLU", "LeakyReLU", ...); throws std::invalid_argument listing the known ones otherwise.
Activation parse_activation(const std::string& name);
/// The lower-case name parse_activation reads back.
const char* activation_name(Activation activation);
/// Every spelling parse_activation reads, with its activation: the lower-case names in the
/// order of the enumeration, then PyTorch's class names (for option tables' accepted
/// values, which list and write back the first spelling of a value).
std::vector<std::pair<std::string, Activation>> activation_spellings();
/// Every activation, in the order of the enumeration.
std::vector<Activation> all_activations();
/// The accepted lower-case names, for messages: "relu, tanh, elu, ...".
std::string activation_names();
/// The TorchScript expression applying it to `x`, e.g. "torch.elu(x)".
std::string activation_torchscript(Activation activation, const std::string& x);
/// The activation of one value, computed in double.
double apply_activation(Activation activation, double value);

}  // namespace upkie_rl
