#include "rl/ppo/tensor_activation.hpp"

#include <stdexcept>
#include <string>

namespace upkie_rl {

namespace {

[[noreturn]] void unknown(Activation activation) {
  throw std::invalid_argument(std::string("no tensor activation for ") +
                              activation_name(activation));
}

}  // namespace

// PyTorch's default parameters throughout, the values policy/activation.cpp computes.
torch::Tensor activate(Activation activation, const torch::Tensor& x) {
  switch (activation) {
    case Activation::kReLU:
      return torch::relu(x);
    case Activation::kTanh:
      return torch::tanh(x);
    case Activation::kELU:
      return torch::elu(x);
    case Activation::kLeakyReLU:
      return torch::leaky_relu(x);
    case Activation::kSiLU:
      return torch::silu(x);
    case Activation::kGELU:
      return torch::gelu(x);
    case Activation::kSigmoid:
      return torch::sigmoid(x);
    case Activation::kSoftplus:
      return torch::softplus(x);
    case Activation::kSELU:
      return torch::selu(x);
  }
  unknown(activation);
}

void activate_in_place(Activation activation, torch::Tensor& x) {
  switch (activation) {
    case Activation::kReLU:
      x.relu_();
      return;
    case Activation::kTanh:
      x.tanh_();
      return;
    case Activation::kELU:
      torch::elu_(x);
      return;
    case Activation::kLeakyReLU:
      torch::leaky_relu_(x);
      return;
    case Activation::kSiLU:
      torch::silu_(x);
      return;
    case Activation::kGELU:
      torch::gelu_(x);
      return;
    case Activation::kSigmoid:
      x.sigmoid_();
      return;
    case Activation::kSoftplus:
      // No softplus_ in libtorch: the element-wise kernel writes its output over its input.
      torch::softplus_out(x, x);
      return;
    case Activation::kSELU:
      torch::selu_(x);
      return;
  }
  unknown(activation);
}

}  // namespace upkie_rl
