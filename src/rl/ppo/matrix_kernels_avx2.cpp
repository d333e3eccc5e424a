#include "rl/ppo/matrix_kernels_avx2.hpp"

#include <algorithm>
#include <stdexcept>

// GCC and Clang on x86-64 compile functions for AVX2 and FMA by attribute, whatever the
// build's target; elsewhere only the stubs at the end exist.
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define UPKIE_RL_MATRIX_KERNELS_AVX2 1
#endif

namespace upkie_rl {

#ifdef UPKIE_RL_MATRIX_KERNELS_AVX2

namespace {

template <bool Masked>
__attribute__((target("avx2,fma"))) inline __m256 load(const float* p, __m256i mask) {
  if constexpr (Masked) {
    return _mm256_maskload_ps(p, mask);
  } else {
    return _mm256_loadu_ps(p);
  }
}

template <bool Masked>
__attribute__((target("avx2,fma"))) inline __m256 finish(const GemmArguments& g, __m256 y,
                                                         std::int64_t offset, __m256i mask) {
  switch (g.epilogue) {
    case GemmEpilogue::kNone:
      return y;
    case GemmEpilogue::kRelu:
      return _mm256_max_ps(y, _mm256_setzero_ps());
    case GemmEpilogue::kReluGate: {
      const __m256 gate = load<Masked>(g.gate + offset, mask);
      return _mm256_and_ps(y, _mm256_cmp_ps(gate, _mm256_setzero_ps(), _CMP_GT_OQ));
    }
    case GemmEpilogue::kTanhGate: {
      const __m256 gate = load<Masked>(g.gate + offset, mask);
      return _mm256_mul_ps(y, _mm256_sub_ps(_mm256_set1_ps(1.0f), _mm256_mul_ps(gate, gate)));
    }
  }
  return y;
}

// How A is laid out, known at compile time so that the inner loop needs no address
// arithmetic: rows of A contiguous (a_depth_stride = 1: x and ∂y as they are), columns of A
// contiguous (a_row_stride = 1: ∂y read transposed), or anything else.
enum class Layout { kRowMajor, kColumnMajor, kStrided };

// Rows x (8·Vectors) block of C at (row, column), accumulated in registers over the whole
// depth. Masked: one vector of which only the first `width` lanes exist (the last columns).
template <int Rows, int Vectors, bool Masked, Layout A>
__attribute__((target("avx2,fma"))) inline void gemm_block(const GemmArguments& g, std::int64_t row,
                                                           std::int64_t column, int width) {
  static_assert(!Masked || Vectors == 1);
  const __m256i mask =
      _mm256_cmpgt_epi32(_mm256_set1_epi32(width), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
  // Locals, and loops unrolled before scalar replacement, so that the accumulators stay
  // in registers (GCC otherwise keeps the array on the stack).
  const std::int64_t depth = g.k;
  const std::int64_t a_row_stride = A == Layout::kColumnMajor ? 1 : g.a_row_stride;
  const std::int64_t a_depth_stride = A == Layout::kRowMajor ? 1 : g.a_depth_stride;
  const std::int64_t ldb = g.ldb;
  __m256 sum[Rows][Vectors];
#pragma GCC unroll 8
  for (int v = 0; v < Vectors; ++v) {
    const __m256 start =
        g.bias != nullptr ? load<Masked>(g.bias + column + 8 * v, mask) : _mm256_setzero_ps();
#pragma GCC unroll 8
    for (int i = 0; i < Rows; ++i) sum[i][v] = start;
  }
  const float* a_rows[Rows];
#pragma GCC unroll 8
  for (int i = 0; i < Rows; ++i) a_rows[i] = g.a + (row + i) * a_row_stride;
  const float* b = g.b + column;
#pragma GCC unroll 2
  for (std::int64_t p = 0; p < depth; ++p) {
    __m256 b_row[Vectors];
#pragma GCC unroll 8
    for (int v = 0; v < Vectors; ++v) b_row[v] = load<Masked>(b + 8 * v, mask);
    b += ldb;
#pragma GCC unroll 8
    for (int i = 0; i < Rows; ++i) {
      const float* a = A == Layout::kRowMajor      ? a_rows[i] + p
                       : A == Layout::kColumnMajor ? a_rows[0] + p * a_depth_stride + i
                                                   : a_rows[i] + p * a_depth_stride;
      const __m256 a_value = _mm256_broadcast_ss(a);
#pragma GCC unroll 8
      for (int v = 0; v < Vectors; ++v) sum[i][v] = _mm256_fmadd_ps(a_value, b_row[v], sum[i][v]);
    }
  }
#pragma GCC unroll 8
  for (int i = 0; i < Rows; ++i) {
    const std::int64_t offset = (row + i) * g.ldc + column;
#pragma GCC unroll 8
    for (int v = 0; v < Vectors; ++v) {
      const __m256 y = finish<Masked>(g, sum[i][v], offset + 8 * v, mask);
      if constexpr (Masked) {
        _mm256_maskstore_ps(g.c + offset, mask, y);
      } else {
        _mm256_storeu_ps(g.c + offset + 8 * v, y);
      }
    }
  }
}

template <int Rows, Layout A>
__attribute__((target("avx2,fma"))) inline void gemm_rows(const GemmArguments& g,
                                                          std::int64_t row) {
  std::int64_t column = 0;
  for (; column + 16 <= g.n; column += 16) gemm_block<Rows, 2, false, A>(g, row, column, 8);
  if (column + 8 <= g.n) {
    gemm_block<Rows, 1, false, A>(g, row, column, 8);
    column += 8;
  }
  if (column < g.n) gemm_block<Rows, 1, true, A>(g, row, column, static_cast<int>(g.n - column));
}

template <Layout A>
__attribute__((target("avx2,fma"))) void gemm_layout(const GemmArguments& g) {
  std::int64_t row = 0;
  for (; row + 6 <= g.m; row += 6) gemm_rows<6, A>(g, row);
  switch (g.m - row) {
    case 5:
      gemm_rows<5, A>(g, row);
      break;
    case 4:
      gemm_rows<4, A>(g, row);
      break;
    case 3:
      gemm_rows<3, A>(g, row);
      break;
    case 2:
      gemm_rows<2, A>(g, row);
      break;
    case 1:
      gemm_rows<1, A>(g, row);
      break;
    default:
      break;
  }
}

// One column of C (a layer with one output): dot products along contiguous rows of A.
__attribute__((target("avx2,fma"))) void gemv_avx2(const GemmArguments& g) {
  const __m256i lanes = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  for (std::int64_t row = 0; row < g.m; ++row) {
    const float* a = g.a + row * g.a_row_stride;
    __m256 sum = _mm256_setzero_ps();
    std::int64_t p = 0;
    for (; p + 8 <= g.k; p += 8) {
      sum = _mm256_fmadd_ps(_mm256_loadu_ps(a + p), _mm256_loadu_ps(g.b + p), sum);
    }
    if (p < g.k) {
      const __m256i mask = _mm256_cmpgt_epi32(_mm256_set1_epi32(static_cast<int>(g.k - p)), lanes);
      sum =
          _mm256_fmadd_ps(_mm256_maskload_ps(a + p, mask), _mm256_maskload_ps(g.b + p, mask), sum);
    }
    __m128 half = _mm_add_ps(_mm256_castps256_ps128(sum), _mm256_extractf128_ps(sum, 1));
    half = _mm_add_ps(half, _mm_movehl_ps(half, half));
    half = _mm_add_ss(half, _mm_movehdup_ps(half));
    float y = _mm_cvtss_f32(half) + (g.bias != nullptr ? g.bias[0] : 0.0f);
    const float gate = g.gate != nullptr ? g.gate[row * g.ldc] : 0.0f;
    switch (g.epilogue) {
      case GemmEpilogue::kNone:
        break;
      case GemmEpilogue::kRelu:
        y = std::max(y, 0.0f);
        break;
      case GemmEpilogue::kReluGate:
        y = gate > 0.0f ? y : 0.0f;
        break;
      case GemmEpilogue::kTanhGate:
        y *= 1.0f - gate * gate;
        break;
    }
    g.c[row * g.ldc] = y;
  }
}

}  // namespace

// Picks the inner loop for A's layout, so that it needs no address arithmetic.
__attribute__((target("avx2,fma"))) void gemm_avx2(const GemmArguments& g) {
  if (g.n == 1 && g.a_depth_stride == 1 && g.ldb == 1) {
    gemv_avx2(g);
  } else if (g.a_depth_stride == 1) {
    gemm_layout<Layout::kRowMajor>(g);
  } else if (g.a_row_stride == 1) {
    gemm_layout<Layout::kColumnMajor>(g);
  } else {
    gemm_layout<Layout::kStrided>(g);
  }
}

__attribute__((target("avx2,fma"))) void transpose_avx2(const float* src, std::int64_t rows,
                                                        std::int64_t columns, float* dst) {
  std::int64_t row = 0;
  for (; row + 8 <= rows; row += 8) {
    std::int64_t column = 0;
    for (; column + 8 <= columns; column += 8) {
      __m256 r[8], t[8];
      for (int i = 0; i < 8; ++i) r[i] = _mm256_loadu_ps(src + (row + i) * columns + column);
      for (int i = 0; i < 8; i += 2) {
        t[i] = _mm256_unpacklo_ps(r[i], r[i + 1]);
        t[i + 1] = _mm256_unpackhi_ps(r[i], r[i + 1]);
      }
      for (int i = 0; i < 8; i += 4) {
        r[i] = _mm256_shuffle_ps(t[i], t[i + 2], _MM_SHUFFLE(1, 0, 1, 0));
        r[i + 1] = _mm256_shuffle_ps(t[i], t[i + 2], _MM_SHUFFLE(3, 2, 3, 2));
        r[i + 2] = _mm256_shuffle_ps(t[i + 1], t[i + 3], _MM_SHUFFLE(1, 0, 1, 0));
        r[i + 3] = _mm256_shuffle_ps(t[i + 1], t[i + 3], _MM_SHUFFLE(3, 2, 3, 2));
      }
      for (int i = 0; i < 4; ++i) {
        _mm256_storeu_ps(dst + (column + i) * rows + row,
                         _mm256_permute2f128_ps(r[i], r[i + 4], 0x20));
        _mm256_storeu_ps(dst + (column + i + 4) * rows + row,
                         _mm256_permute2f128_ps(r[i], r[i + 4], 0x31));
      }
    }
    for (; column < columns; ++column) {
      for (std::int64_t i = row; i < row + 8; ++i)
        dst[column * rows + i] = src[i * columns + column];
    }
  }
  for (; row < rows; ++row) {
    for (std::int64_t column = 0; column < columns; ++column) {
      dst[column * rows + row] = src[row * columns + column];
    }
  }
}

bool cpu_has_avx2_fma() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
}

#else

bool cpu_has_avx2_fma() { return false; }
void gemm_avx2(const GemmArguments&) {
  throw std::logic_error("gemm_avx2: this build has no AVX2 kernel");
}
void transpose_avx2(const float*, std::int64_t, std::int64_t, float*) {
  throw std::logic_error("transpose_avx2: this build has no AVX2 kernel");
}

#endif

}  // namespace upkie_rl
