#pragma once
/// @file
/// tensor_values(): the values of a contiguous float32 CPU tensor as a span, no copy.

#include <cstddef>
#include <span>

#include <torch/torch.h>

namespace upkie_rl {

/// The values of `tensor`, which must be a contiguous float32 CPU tensor: the rollout's and
/// the policy's own buffers, made so by their owners (a minibatch from outside is checked
/// first, PpoGradient). Why a span: the hand-written gradient, GAE and the mirror map work
/// on plain floats, and a span carries the length with the pointer.
inline std::span<float> tensor_values(torch::Tensor& tensor) {
  return {tensor.data_ptr<float>(), static_cast<std::size_t>(tensor.numel())};
}

/// The same, read-only.
inline std::span<const float> tensor_values(const torch::Tensor& tensor) {
  return {tensor.data_ptr<float>(), static_cast<std::size_t>(tensor.numel())};
}

}  // namespace upkie_rl
