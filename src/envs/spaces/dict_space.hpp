#pragma once
/// @file
/// A dictionary of Box spaces, e.g. the servos view: one entry per joint, each a Box whose
/// components are that joint's keys (position, velocity, ...).

#include <string>
#include <utility>
#include <vector>

#include "envs/spaces/box_space.hpp"

namespace upkie_rl {

/// Gymnasium's Dict of Boxes, in insertion order (used for listings).
struct DictSpace {
  std::vector<std::pair<std::string, BoxSpace>> entries;

  /// Total number of components of all entries.
  std::size_t flat_size() const {
    std::size_t size = 0;
    for (const auto& entry : entries) size += entry.second.size();
    return size;
  }

  /// The flat Box of every entry, component names prefixed by "<entry>.".
  BoxSpace flatten() const {
    BoxSpace flat;
    for (const auto& [key, box] : entries) {
      for (std::size_t i = 0; i < box.size(); ++i) {
        flat.add(key + "." + box.names[i], box.low[i], box.high[i]);
      }
    }
    return flat;
  }
};

}  // namespace upkie_rl
