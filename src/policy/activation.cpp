#include "policy/activation.hpp"

#include <stdexcept>

namespace upkie_rl {

Activation parse_activation(const std::string& name) {
  if (name == "relu" || name == "ReLU") return Activation::kReLU;
  if (name == "tanh" || name == "Tanh") return Activation::kTanh;
  throw std::invalid_argument("unknown activation '" + name + "' (expected relu or tanh)");
}

const char* activation_name(Activation activation) {
  return activation == Activation::kReLU ? "relu" : "tanh";
}

}  // namespace upkie_rl
