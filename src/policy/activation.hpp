#pragma once
/// @file
/// Activation of the hidden layers of the policy and value networks.

#include <string>

namespace upkie_rl {

enum class Activation { kReLU, kTanh };

/// Parses "relu" or "tanh"; throws std::invalid_argument otherwise.
Activation parse_activation(const std::string& name);
const char* activation_name(Activation activation);

}  // namespace upkie_rl
