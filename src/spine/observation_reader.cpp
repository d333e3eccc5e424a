#include "spine/observation_reader.hpp"

#include <string>
#include <string_view>

#include "sim/observation_fields.hpp"
#include "spine/spine_error.hpp"

namespace upkie_rl {
namespace {

/// Key path for error messages, formatted only when throwing.
struct KeyPath {
  const KeyPath* parent;
  std::string_view key;
  std::string format() const {
    std::string text = parent != nullptr ? parent->format() + "." : std::string();
    text += key;
    return text;
  }
};

[[noreturn]] void fail(const KeyPath& path, std::string_view problem) {
  throw SpineError("spine observation key '" + path.format() + "' " + std::string(problem));
}

const msgpack::object* find(const msgpack::object& map, std::string_view key) {
  if (map.type != msgpack::type::MAP) return nullptr;
  for (std::uint32_t i = 0; i < map.via.map.size; ++i) {
    const msgpack::object& candidate = map.via.map.ptr[i].key;
    if (candidate.type == msgpack::type::STR &&
        std::string_view(candidate.via.str.ptr, candidate.via.str.size) == key) {
      return &map.via.map.ptr[i].val;
    }
  }
  return nullptr;
}

double number(const msgpack::object& value, const KeyPath& path) {
  switch (value.type) {
    case msgpack::type::FLOAT32:
    case msgpack::type::FLOAT64:
      return value.via.f64;
    case msgpack::type::POSITIVE_INTEGER:
      return static_cast<double>(value.via.u64);
    case msgpack::type::NEGATIVE_INTEGER:
      return static_cast<double>(value.via.i64);
    default:
      fail(path, "is not a number");
  }
}

/// Reads an array of exactly `size` numbers.
void numbers(const msgpack::object& value, const KeyPath& path, double* out, std::uint32_t size) {
  if (value.type != msgpack::type::ARRAY || value.via.array.size != size) {
    fail(path, "is not an array of " + std::to_string(size) + " numbers");
  }
  for (std::uint32_t i = 0; i < size; ++i) out[i] = number(value.via.array.ptr[i], path);
}

/// Reads a spine observation map by walking the declaration of sim/observation_fields.hpp.
class MsgpackObservationReader {
 public:
  MsgpackObservationReader(const msgpack::object& map, const KeyPath* path)
      : map_(map), path_(path) {}

  template <typename Children>
  void map(std::string_view key, KeyPresence presence, Children&& children) {
    const KeyPath path{path_, key};
    read_map(path, lookup(path, presence), children);
  }
  template <typename Children>
  void map_if(std::string_view key, bool& flag, Children&& children) {
    const KeyPath path{path_, key};
    const msgpack::object* value = find(map_, key);
    flag = value != nullptr;
    read_map(path, value, children);
  }
  void real(std::string_view key, double& out, KeyPresence presence) {
    const KeyPath path{path_, key};
    if (const msgpack::object* value = lookup(path, presence)) out = number(*value, path);
  }
  void boolean(std::string_view key, bool& out, KeyPresence presence) {
    const KeyPath path{path_, key};
    const msgpack::object* value = lookup(path, presence);
    if (value == nullptr) return;
    if (value->type != msgpack::type::BOOLEAN) fail(path, "is not a bool");
    out = value->via.boolean;
  }
  void vector3(std::string_view key, Eigen::Vector3d& out, KeyPresence presence) {
    const KeyPath path{path_, key};
    if (const msgpack::object* value = lookup(path, presence)) numbers(*value, path, out.data(), 3);
  }
  void quaternion(std::string_view key, Eigen::Quaterniond& out, KeyPresence presence) {
    const KeyPath path{path_, key};
    const msgpack::object* value = lookup(path, presence);
    if (value == nullptr) return;
    double wxyz[4];
    numbers(*value, path, wxyz, 4);
    out = Eigen::Quaterniond(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
  }
  void matrix3(std::string_view key, Eigen::Matrix3d& out, KeyPresence presence) {
    const KeyPath path{path_, key};
    const msgpack::object* value = lookup(path, presence);
    if (value == nullptr) return;
    double row_major[9];
    numbers(*value, path, row_major, 9);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) out(i, j) = row_major[3 * i + j];
    }
  }
  /// Values the typed Observation does not carry are not read.
  template <typename Value>
  void computed(std::string_view, Value&&) {}

 private:
  /// Reads map `value` (at `path`; nothing when null) with `children`.
  template <typename Children>
  void read_map(const KeyPath& path, const msgpack::object* value, Children&& children) const {
    if (value == nullptr) return;
    if (value->type != msgpack::type::MAP) fail(path, "is not a map");
    MsgpackObservationReader fields(*value, &path);
    children(fields);
  }
  /// The value at `path.key`, or nullptr when an optional key is absent.
  const msgpack::object* lookup(const KeyPath& path, KeyPresence presence) const {
    const msgpack::object* value = find(map_, path.key);
    if (value == nullptr && presence == KeyPresence::kRequired) fail(path, "is missing");
    return value;
  }

  const msgpack::object& map_;
  const KeyPath* path_;
};

}  // namespace

void read_observation(const msgpack::object& message, Observation& observation) {
  if (message.type != msgpack::type::MAP) {
    throw SpineError("spine observation is not a map");
  }
  MsgpackObservationReader reader(message, nullptr);
  visit_observation_fields(observation, reader);
}

}  // namespace upkie_rl
