#pragma once
/// @file
/// A Box space: a vector of float32 values, each within [low, high] (bounds may be infinite).

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace upkie_rl {

/// Gymnasium's Box with float32 bounds, one dimension.
struct BoxSpace {
  std::vector<float> low;          ///< Lower bound of each component (may be -inf).
  std::vector<float> high;         ///< Upper bound of each component (may be +inf).
  std::vector<std::string> names;  ///< Name of each component, for records and listings.

  /// Number of components.
  std::size_t size() const { return low.size(); }

  /// Appends one component.
  void add(std::string name, float lower, float upper) {
    names.push_back(std::move(name));
    low.push_back(lower);
    high.push_back(upper);
  }

  /// Index of the component called `name`, or size() when there is none.
  std::size_t index_of(const std::string& name) const;

  /// "Box(4: theta [-3.14, 3.14], ...)", for listings.
  std::string describe() const;
};

/// Clamps `action` into `space`, writing the result to `clamped` (both of size
/// space.size()); allocation-free unless it throws.
/// @param allow_nan Indices (sorted or not) of components where NaN is a legal value that
///        passes unchanged (the servos' "no position loop"); empty for none.
/// @throws std::invalid_argument naming the space's component when the size is wrong or a
///         component is NaN (outside allow_nan) or infinite.
void clamp_to_space(const BoxSpace& space, std::span<const float> action, std::span<float> clamped,
                    std::span<const std::size_t> allow_nan = {});

}  // namespace upkie_rl
