#include "envs/spaces/mirror_symmetry.hpp"

#include <stdexcept>

namespace upkie_rl {

SignedPermutation::SignedPermutation(std::vector<std::size_t> source, std::vector<bool> negate,
                                     const std::string& what)
    : source_(std::move(source)), negate_(std::move(negate)) {
  if (negate_.size() != source_.size()) {
    throw std::invalid_argument(what + " mirror: " + std::to_string(source_.size()) +
                                " sources but " + std::to_string(negate_.size()) + " signs");
  }
  for (std::size_t i = 0; i < source_.size(); ++i) {
    const std::size_t j = source_[i];
    if (j >= source_.size()) {
      throw std::invalid_argument(what + " mirror: component " + std::to_string(i) +
                                  " takes component " + std::to_string(j) + " of " +
                                  std::to_string(source_.size()));
    }
    // Applied twice, component i is ±in[source[j]] with the sign negate[i] xor negate[j].
    if (source_[j] != i || negate_[i] != negate_[j]) {
      throw std::invalid_argument(what + " mirror: not an involution at component " +
                                  std::to_string(i));
    }
  }
}

void SignedPermutation::apply(std::span<const float> in, std::span<float> out) const {
  const std::size_t n = source_.size();
  if (n == 0 || in.size() != out.size() || in.size() % n != 0) {
    throw std::invalid_argument("mirror of " + std::to_string(in.size()) + " values into " +
                                std::to_string(out.size()) + ": rows of " + std::to_string(n));
  }
  for (std::size_t row = 0; row < in.size(); row += n) {
    for (std::size_t i = 0; i < n; ++i) {
      const float value = in[row + source_[i]];
      out[row + i] = negate_[i] ? -value : value;
    }
  }
}

SignedPermutation SignedPermutation::repeated(std::size_t copies) const {
  SignedPermutation result;
  const std::size_t n = source_.size();
  for (std::size_t copy = 0; copy < copies; ++copy) {
    for (std::size_t i = 0; i < n; ++i) {
      result.source_.push_back(copy * n + source_[i]);
      result.negate_.push_back(negate_[i]);
    }
  }
  return result;
}

}  // namespace upkie_rl
