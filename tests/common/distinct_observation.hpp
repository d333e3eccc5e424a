#pragma once
/// @file
/// A test helper that walks the observation declaration (sim/observation_fields.hpp) to
/// give every field a distinct value.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string_view>

#include "sim/observation_fields.hpp"

namespace upkie_rl::testing {

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
