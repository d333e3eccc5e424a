#pragma once
/// @file
/// backward_layer_avx2: one dense layer's backward pass (y = W·x + b, row-major batches) on
/// the AVX2/FMA matrix kernels of matrix_kernels_avx2.hpp, for the hand-written PPO gradient
/// (rl/ppo/ppo_gradient.hpp). It knows layers, not PPO. Call it only when cpu_has_avx2_fma()
/// is true (PpoGradient checks it once and uses Eigen otherwise); like the kernels, it is
/// compiled for baseline x86-64 and reaches AVX2 through their function attributes.

#include <cstdint>

#include "policy/parameter_layout.hpp"

namespace upkie_rl {

/// The operands of backward_layer_avx2, for designated initializers. Matrices are row-major
/// float32 with `rows` batch rows; the layer's shapes come from `layer`.
struct DenseBackwardArguments {
  DenseLayerLayout layer;           ///< in, out (and offsets, unused here).
  std::int64_t rows = 0;            ///< Batch rows.
  const float* input = nullptr;     ///< x: rows x in, the layer's input.
  const float* weight = nullptr;    ///< W: out x in.
  const float* d_output = nullptr;  ///< ∂L/∂y: rows x out (y before this layer's activation).
  /// The layer below's activated output (our input), or null for the first layer: then no
  /// ∂L/∂z of the layer below is computed.
  const float* gate = nullptr;
  bool relu = false;          ///< The layer below's activation: relu, else tanh.
  float* scratch = nullptr;   ///< in x out floats of workspace.
  float* d_weight = nullptr;  ///< ∂L/∂W: out x in, overwritten.
  float* d_bias = nullptr;    ///< ∂L/∂b: out, overwritten.
  float* d_input = nullptr;   ///< ∂L/∂z of the layer below: rows x in, written when gate.
};

/// ∂b = 1ᵀ·∂y, ∂W = ∂yᵀ·x and, when `gate` is not null, ∂z of the layer below = (∂y·W)
/// through its activation (relu or tanh, whose output is `gate`).
void backward_layer_avx2(const DenseBackwardArguments& arguments);

}  // namespace upkie_rl
