#pragma once
/// @file
/// The spine's persistent, typed dictionary: configuration and action messages are merged
/// into it, with the typing rules of the Upkie spine (spine.md section 3).

#include <cstdint>
#include <map>
#include <memory>
#include <msgpack.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace upkie_rl {

/// A tree of string-keyed maps whose leaves are typed values. Arrays are typed by their
/// length (2: vector2, 3: vector3, 4: quaternion [w, x, y, z], 9: 3x3 matrix row-major,
/// other: vector) and must hold numbers. Merging a message keeps keys it does not mention
/// and refuses nil, binary and extension values, non-string keys, and any key whose type
/// differs from the one it already has (int and float are different types).
class Dictionary {
 public:
  struct Path;  ///< Key path of a value being merged (for error messages).
  enum class Kind {
    kMap,
    kBool,
    kInt,
    kFloat,
    kString,
    kVector2,
    kVector3,
    kQuaternion,
    kMatrix3,
    kVector
  };

  Dictionary() = default;
  Dictionary(const Dictionary&) = delete;
  Dictionary& operator=(const Dictionary&) = delete;
  Dictionary(Dictionary&&) noexcept = default;
  Dictionary& operator=(Dictionary&&) noexcept = default;

  /// Merges a msgpack map into this map.
  /// @throws SpineError naming the key path and the problem; on error the dictionary
  ///         may be partly updated (the spine shuts down anyway).
  void update(const msgpack::object& message);

  /// Removes every key (becomes an empty map).
  void clear();

  Kind kind() const { return kind_; }
  bool is_map() const { return kind_ == Kind::kMap; }
  bool has(std::string_view key) const;
  /// Child of a map. @throws SpineError when this is not a map or lacks the key.
  const Dictionary& at(std::string_view key) const;
  /// Number of keys of a map (0 for a value).
  std::size_t size() const { return children_.size(); }

  /// Value of a bool. @throws SpineError for another kind.
  bool as_bool() const;
  /// Value of an int or float, as a double. @throws SpineError for another kind.
  double as_number() const;
  /// Value of a string. @throws SpineError for another kind.
  const std::string& as_string() const;
  /// Elements of an array of any length kind. @throws SpineError for another kind.
  const std::vector<double>& as_array() const;

  /// Name of a kind, for messages ("float", "vector3", ...).
  static std::string_view kind_name(Kind kind);

 private:
  void update_map(const msgpack::object& message, const Path* path, int depth);
  void assign(const msgpack::object& value, const Path* path, int depth, bool fresh);

  Kind kind_ = Kind::kMap;
  std::map<std::string, std::unique_ptr<Dictionary>, std::less<>> children_;
  bool bool_ = false;
  std::int64_t int_ = 0;
  double float_ = 0.0;
  std::string string_;
  std::vector<double> array_;
};

}  // namespace upkie_rl
