#pragma once
/// @file
/// The one walk over an Observation's nested-dictionary view (the Upkie spine's keys), shared
/// by every writer of that view: it writes the declaration of sim/observation_fields.hpp.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <string_view>
#include <type_traits>

#include "sim/observation.hpp"
#include "sim/observation_dict.hpp"
#include "sim/observation_fields.hpp"

namespace upkie_rl {

namespace detail {

/// Counts the keys a map declares (a msgpack map's header needs its size first).
struct ObservationKeyCounter {
  std::size_t count = 0;
  template <typename Children>
  void map(std::string_view, KeyPresence, Children&&) {
    ++count;
  }
  template <typename Children>
  void map_if(std::string_view, bool flag, Children&&) {
    if (flag) ++count;
  }
  template <typename Field>
  void real(std::string_view, Field&, KeyPresence) {
    ++count;
  }
  template <typename Field>
  void boolean(std::string_view, Field&, KeyPresence) {
    ++count;
  }
  template <typename Field>
  void vector3(std::string_view, Field&, KeyPresence) {
    ++count;
  }
  template <typename Field>
  void quaternion(std::string_view, Field&, KeyPresence) {
    ++count;
  }
  template <typename Field>
  void matrix3(std::string_view, Field&, KeyPresence) {
    ++count;
  }
  template <typename Value>
  void computed(std::string_view, Value&&) {
    ++count;
  }
};

/// Turns the declaration's visits into calls of a Writer (see walk_observation).
template <typename Writer>
class ObservationFieldWriter {
 public:
  explicit ObservationFieldWriter(Writer& writer) : writer_(writer) {}

  template <typename Children>
  void map(std::string_view key, KeyPresence, Children&& children) {
    writer_.key(key);
    write_map(children);
  }
  template <typename Children>
  void map_if(std::string_view key, bool flag, Children&& children) {
    if (flag) map(key, KeyPresence::kOptional, children);
  }
  void real(std::string_view key, double value, KeyPresence) {
    writer_.key(key);
    writer_.real(value);
  }
  void boolean(std::string_view key, bool value, KeyPresence) {
    writer_.key(key);
    writer_.boolean(value);
  }
  void vector3(std::string_view key, const Eigen::Vector3d& vector, KeyPresence) {
    writer_.key(key);
    writer_.reals(vector.data(), 3);
  }
  void quaternion(std::string_view key, const Eigen::Quaterniond& quaternion, KeyPresence) {
    const double wxyz[4] = {quaternion.w(), quaternion.x(), quaternion.y(), quaternion.z()};
    writer_.key(key);
    writer_.reals(wxyz, 4);
  }
  void matrix3(std::string_view key, const Eigen::Matrix3d& matrix, KeyPresence) {
    double row_major[9];
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) row_major[3 * i + j] = matrix(i, j);
    }
    writer_.key(key);
    writer_.reals(row_major, 9);
  }
  template <typename Value>
  void computed(std::string_view key, Value&& value) {
    using Result = std::decay_t<decltype(value())>;
    if constexpr (std::is_same_v<Result, bool>) {
      boolean(key, value(), KeyPresence::kOptional);
    } else if constexpr (std::is_same_v<Result, int>) {
      writer_.key(key);
      writer_.integer(value());
    } else if constexpr (std::is_same_v<Result, double>) {
      real(key, value(), KeyPresence::kOptional);
    } else {
      vector3(key, value(), KeyPresence::kOptional);
    }
  }

  /// Writes the map whose keys `children(visitor)` declares.
  template <typename Children>
  void write_map(Children& children) {
    ObservationKeyCounter counter;
    children(counter);
    writer_.begin_map(counter.count);
    children(*this);
    writer_.end_map();
  }

 private:
  Writer& writer_;
};

}  // namespace detail

/// Walks the observation tree once, in sorted key order, calling `writer`: begin_map(size),
/// end_map(), key(string_view), real(double), boolean(bool), integer(int),
/// reals(const double*, size). Every dictionary view (JSON, msgpack, Python) comes from
/// this one walk of the declaration in sim/observation_fields.hpp, so they cannot
/// disagree; the simulated values are documented in sim/observation_dict.hpp.
template <typename Writer>
void walk_observation(const Observation& observation, Writer& writer) {
  detail::ObservationFieldWriter<Writer> fields(writer);
  auto root = [&](auto& visitor) { visit_observation_fields(observation, visitor); };
  fields.write_map(root);
}

}  // namespace upkie_rl
