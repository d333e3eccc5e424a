#include "rl/ppo/dense_layer_backward_avx2.hpp"

#include "rl/ppo/matrix_kernels_avx2.hpp"

namespace upkie_rl {

void backward_layer_avx2(const DenseBackwardArguments& arguments) {
  const DenseLayerLayout& layer = arguments.layer;
  const std::int64_t rows = arguments.rows;
  const float* in_data = arguments.input;
  const float* weight = arguments.weight;
  const float* d_output = arguments.d_output;
  const float* gate = arguments.gate;
  float* scratch = arguments.scratch;
  float* d_weight = arguments.d_weight;
  float* d_bias = arguments.d_bias;
  float* d_input = arguments.d_input;
  // ∂b = 1ᵀ·∂y: A is a row of ones (one value, strides 0).
  static constexpr float kOne = 1.0f;
  gemm_avx2({.m = 1,
             .n = layer.out,
             .k = rows,
             .a = &kOne,
             .b = d_output,
             .ldb = layer.out,
             .c = d_bias,
             .ldc = layer.out});
  if (layer.in < 16 && layer.in < layer.out) {
    // Few inputs (the observation): ∂Wᵀ = xᵀ·∂y has the longer rows, then transpose.
    gemm_avx2({.m = layer.in,
               .n = layer.out,
               .k = rows,
               .a = in_data,
               .a_row_stride = 1,
               .a_depth_stride = layer.in,
               .b = d_output,
               .ldb = layer.out,
               .c = scratch,
               .ldc = layer.out});
    transpose_avx2(scratch, layer.in, layer.out, d_weight);
  } else {
    // ∂W = ∂yᵀ·x: A is ∂y read transposed.
    gemm_avx2({.m = layer.out,
               .n = layer.in,
               .k = rows,
               .a = d_output,
               .a_row_stride = 1,
               .a_depth_stride = layer.out,
               .b = in_data,
               .ldb = layer.in,
               .c = d_weight,
               .ldc = layer.in});
  }
  if (gate != nullptr) {
    // ∂z of the layer below = (∂y·W) through its activation, whose output is our input.
    gemm_avx2({.m = rows,
               .n = layer.in,
               .k = layer.out,
               .a = d_output,
               .a_row_stride = layer.out,
               .a_depth_stride = 1,
               .b = weight,
               .ldb = layer.in,
               .c = d_input,
               .ldc = layer.in,
               .epilogue = arguments.relu ? GemmEpilogue::kReluGate : GemmEpilogue::kTanhGate,
               .gate = gate});
  }
}

}  // namespace upkie_rl
