#pragma once
/// @file
/// Test helpers that walk the observation declaration (sim/observation_fields.hpp): the
/// dotted key path of every entry, and a filler that gives every field a distinct value.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <string_view>
#include <vector>

#include "sim/observation_fields.hpp"

namespace upkie_rl::testing {

/// One leaf of the declaration.
struct ObservationKeyPath {
  std::string path;  ///< Dotted, e.g. "servo.left_hip.position".
  bool computed;     ///< Written only (the typed Observation does not carry it).
  bool required;     ///< A reader refuses a message without it (its map being there).
};

/// Collects every leaf of the declaration, and the keys of each map in declaration order.
class KeyPathCollector {
 public:
  std::vector<ObservationKeyPath> leaves;
  std::vector<ObservationKeyPath> maps;               ///< Every nested map (computed: false).
  std::vector<std::vector<std::string>> map_keys{1};  ///< [0]: the top-level map.

  template <typename Children>
  void map(std::string_view key, KeyPresence presence, Children&& children) {
    add_key(key);
    maps.push_back({prefix_ + std::string(key), false, presence == KeyPresence::kRequired});
    KeyPathCollector child;
    child.prefix_ = prefix_ + std::string(key) + ".";
    children(child);
    leaves.insert(leaves.end(), child.leaves.begin(), child.leaves.end());
    maps.insert(maps.end(), child.maps.begin(), child.maps.end());
    map_keys.insert(map_keys.end(), child.map_keys.begin(), child.map_keys.end());
  }
  template <typename Children>
  void map_if(std::string_view key, bool&, Children&& children) {
    map(key, KeyPresence::kOptional, children);
  }
  template <typename Field>
  void real(std::string_view key, Field&, KeyPresence presence) {
    leaf(key, false, presence);
  }
  template <typename Field>
  void boolean(std::string_view key, Field&, KeyPresence presence) {
    leaf(key, false, presence);
  }
  template <typename Field>
  void vector3(std::string_view key, Field&, KeyPresence presence) {
    leaf(key, false, presence);
  }
  template <typename Field>
  void quaternion(std::string_view key, Field&, KeyPresence presence) {
    leaf(key, false, presence);
  }
  template <typename Field>
  void matrix3(std::string_view key, Field&, KeyPresence presence) {
    leaf(key, false, presence);
  }
  template <typename Value>
  void computed(std::string_view key, Value&&) {
    leaf(key, true, KeyPresence::kOptional);
  }

 private:
  void add_key(std::string_view key) { map_keys.front().emplace_back(key); }
  void leaf(std::string_view key, bool computed, KeyPresence presence) {
    add_key(key);
    leaves.push_back({prefix_ + std::string(key), computed, presence == KeyPresence::kRequired});
  }
  std::string prefix_;
};

/// The declaration's leaves.
inline KeyPathCollector observation_key_paths() {
  Observation observation;
  KeyPathCollector collector;
  visit_observation_fields(observation, collector);
  return collector;
}

/// Gives every field the declaration reads a value of its own (1, 2, 3, ... in walk order;
/// booleans true, quaternions and matrices made of distinct numbers), and has_sim true.
class DistinctValueFiller {
 public:
  template <typename Children>
  void map(std::string_view, KeyPresence, Children&& children) {
    children(*this);
  }
  template <typename Children>
  void map_if(std::string_view, bool& flag, Children&& children) {
    flag = true;
    children(*this);
  }
  void real(std::string_view, double& value, KeyPresence) { value = next(); }
  void boolean(std::string_view, bool& value, KeyPresence) { value = true; }
  void vector3(std::string_view, Eigen::Vector3d& value, KeyPresence) {
    for (int i = 0; i < 3; ++i) value[i] = next();
  }
  void quaternion(std::string_view, Eigen::Quaterniond& value, KeyPresence) {
    for (int i = 0; i < 4; ++i) value.coeffs()[i] = next();
  }
  void matrix3(std::string_view, Eigen::Matrix3d& value, KeyPresence) {
    for (int i = 0; i < 9; ++i) value.data()[i] = next();
  }
  template <typename Value>
  void computed(std::string_view, Value&&) {}

 private:
  double next() { return counter_ += 1.0; }
  double counter_ = 0.0;
};

}  // namespace upkie_rl::testing
