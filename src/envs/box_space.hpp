#pragma once
/// @file
/// A Box space: a vector of float32 values, each within [low, high] (bounds may be infinite).

#include <cstddef>
#include <string>
#include <vector>

namespace upkie_rl {

/// Gymnasium's Box with float32 bounds, one dimension.
struct BoxSpace {
  std::vector<float> low;   ///< Lower bound of each component (may be -inf).
  std::vector<float> high;  ///< Upper bound of each component (may be +inf).
  std::vector<std::string> names;  ///< Name of each component, for records and listings.

  /// Number of components.
  std::size_t size() const { return low.size(); }
};

}  // namespace upkie_rl
