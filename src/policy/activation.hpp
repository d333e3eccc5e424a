#pragma once
/// @file
/// Activation of the hidden layers of the policy and value networks.

#include <string>

namespace upkie_rl {

/// The trainer (rl/) trains ReLU and Tanh networks; the others, with PyTorch's definitions
/// and default parameters, come with policies imported from Stable-Baselines3 and are only
/// evaluated (DeployedPolicy, ONNX export).
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
/// Whether `upkie-rl train` can train networks with it (ReLU and Tanh).
bool is_trainable(Activation activation);
/// The activation of one value, computed in double.
double apply_activation(Activation activation, double value);

}  // namespace upkie_rl
