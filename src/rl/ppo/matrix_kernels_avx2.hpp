#pragma once
/// @file
/// Float32 matrix kernels for small dense layers (tens of rows and columns) on CPUs with
/// AVX2 and FMA: the product C = A·B (+ a bias row) followed by an activation or its
/// derivative, and a transpose. They know nothing of PPO or of libtorch.
///
/// Why: the project is built for baseline x86-64, where Eigen's GEMM only has SSE2 and
/// needs about 1.4 instructions per multiply-add on these shapes; these kernels are compiled
/// for AVX2 and FMA (function attributes, not a build flag) and need about 0.25, the rate
/// of libtorch's AVX2 sgemm. The hand-written PPO gradient (rl/ppo/ppo_gradient.hpp) runs its
/// MLPs' forward and backward passes on them when cpu_has_avx2_fma(), and on Eigen
/// otherwise. Call the other functions only when cpu_has_avx2_fma() is true: on other CPUs
/// they would fault, and where the compiler has no AVX2 (not x86-64 GCC or Clang) they throw
/// std::logic_error.

#include <cstdint>

namespace upkie_rl {

/// What happens to C = A·B (+ bias) before it is stored.
enum class GemmEpilogue {
  kNone,
  /// max(C, 0): a hidden layer's forward pass through relu.
  kRelu,
  /// C where gate > 0, else 0: ∂L/∂z from ∂L/∂y of y = relu(z), with gate = y.
  kReluGate,
  /// C·(1 − gate²): ∂L/∂z from ∂L/∂y of y = tanh(z), with gate = y.
  kTanhGate,
};

/// The operands of gemm_avx2: C (m x n) = A (m x k) · B (k x n) (+ bias), then the epilogue.
/// Meant for designated initializers; fields left out keep their defaults.
struct GemmArguments {
  std::int64_t m = 0;  ///< Rows of C and of A.
  std::int64_t n = 0;  ///< Columns of C and of B.
  std::int64_t k = 0;  ///< Depth: columns of A, rows of B.
  /// A(r, p) = a[r·a_row_stride + p·a_depth_stride]: A can be row-major (depth stride 1), a
  /// transposed view (row stride 1), or one value repeated (both strides 0).
  const float* a = nullptr;
  std::int64_t a_row_stride = 0;
  std::int64_t a_depth_stride = 0;
  const float* b = nullptr;  ///< Row-major, leading dimension ldb.
  std::int64_t ldb = 0;
  float* c = nullptr;  ///< Row-major, leading dimension ldc; overwritten.
  std::int64_t ldc = 0;
  const float* bias = nullptr;  ///< n values added to every row of C, or null.
  GemmEpilogue epilogue = GemmEpilogue::kNone;
  const float* gate = nullptr;  ///< Laid out like C, read by the gate epilogues.
};

/// Whether this CPU has AVX2 and FMA (and this build the kernels): whether the functions
/// below may be called.
bool cpu_has_avx2_fma();

/// C = A·B (+ bias), then the epilogue, accumulated in registers over the whole depth (no
/// allocation). A layer with one output (n = 1, A row-major, B a column) takes a dot
/// product per row.
void gemm_avx2(const GemmArguments& arguments);

/// dst (columns x rows, row-major) = srcᵀ (src: rows x columns, row-major), by 8x8 blocks
/// in registers (Eigen's transposed copy goes element by element). src and dst must not
/// overlap.
void transpose_avx2(const float* src, std::int64_t rows, std::int64_t columns, float* dst);

}  // namespace upkie_rl
