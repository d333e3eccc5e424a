#include "spine/dictionary.hpp"

#include <limits>

#include "spine/spine_error.hpp"

namespace upkie_rl {

/// Key path of the value being merged, as a chain on the stack: formatted only for errors.
struct Dictionary::Path {
  const Path* parent;
  std::string_view key;
  std::string format() const {
    std::string text = parent != nullptr ? parent->format() : std::string();
    if (!text.empty()) text += '.';
    text += key;
    return text;
  }
};

namespace {

/// Deeper messages are refused (the unpacker limits depth too; this guards direct use).
constexpr int kMaxDepth = 32;

std::string describe(const Dictionary::Path* path) {
  const std::string text = path != nullptr ? path->format() : std::string();
  return text.empty() ? std::string("the message root") : "key '" + text + "'";
}

Dictionary::Kind array_kind(std::size_t size) {
  switch (size) {
    case 2:
      return Dictionary::Kind::kVector2;
    case 3:
      return Dictionary::Kind::kVector3;
    case 4:
      return Dictionary::Kind::kQuaternion;
    case 9:
      return Dictionary::Kind::kMatrix3;
    default:
      return Dictionary::Kind::kVector;
  }
}

std::string_view msgpack_type_name(msgpack::type::object_type type) {
  switch (type) {
    case msgpack::type::NIL:
      return "nil";
    case msgpack::type::BOOLEAN:
      return "bool";
    case msgpack::type::POSITIVE_INTEGER:
    case msgpack::type::NEGATIVE_INTEGER:
      return "int";
    case msgpack::type::FLOAT32:
    case msgpack::type::FLOAT64:
      return "float";
    case msgpack::type::STR:
      return "str";
    case msgpack::type::BIN:
      return "binary";
    case msgpack::type::ARRAY:
      return "array";
    case msgpack::type::MAP:
      return "map";
    case msgpack::type::EXT:
      return "extension";
  }
  return "unknown";
}

/// The kind `value` takes in a Dictionary.
/// @throws SpineError for a msgpack type the spine refuses (nil, binary, extension).
Dictionary::Kind kind_of(const msgpack::object& value, const Dictionary::Path* path) {
  switch (value.type) {
    case msgpack::type::MAP:
      return Dictionary::Kind::kMap;
    case msgpack::type::BOOLEAN:
      return Dictionary::Kind::kBool;
    case msgpack::type::POSITIVE_INTEGER:
    case msgpack::type::NEGATIVE_INTEGER:
      return Dictionary::Kind::kInt;
    case msgpack::type::FLOAT32:
    case msgpack::type::FLOAT64:
      return Dictionary::Kind::kFloat;
    case msgpack::type::STR:
      return Dictionary::Kind::kString;
    case msgpack::type::ARRAY:
      return array_kind(value.via.array.size);
    default:
      throw SpineError(describe(path) + " has a " + std::string(msgpack_type_name(value.type)) +
                       " value, which the spine refuses");
  }
}

/// The int64 of an integer `value`.
/// @throws SpineError for a positive integer beyond int64.
std::int64_t to_int64(const msgpack::object& value, const Dictionary::Path* path) {
  if (value.type != msgpack::type::POSITIVE_INTEGER) return value.via.i64;
  if (value.via.u64 > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
    throw SpineError(describe(path) + " is an integer too large for int64");
  }
  return static_cast<std::int64_t>(value.via.u64);
}

/// Copies the numbers of array `value` into `out` (resized, no allocation when it fits).
/// @throws SpineError for an element that is not a number.
void copy_numbers(const msgpack::object& value, const Dictionary::Path* path,
                  std::vector<double>& out) {
  const msgpack::object_array& array = value.via.array;
  out.resize(array.size);
  for (std::uint32_t i = 0; i < array.size; ++i) {
    const msgpack::object& element = array.ptr[i];
    switch (element.type) {
      case msgpack::type::FLOAT32:
      case msgpack::type::FLOAT64:
        out[i] = element.via.f64;
        break;
      case msgpack::type::POSITIVE_INTEGER:
        out[i] = static_cast<double>(element.via.u64);
        break;
      case msgpack::type::NEGATIVE_INTEGER:
        out[i] = static_cast<double>(element.via.i64);
        break;
      default:
        throw SpineError(describe(path) + " holds a " +
                         std::string(msgpack_type_name(element.type)) +
                         " in an array, arrays must hold numbers");
    }
  }
}

}  // namespace

std::string_view Dictionary::kind_name(Kind kind) {
  switch (kind) {
    case Kind::kMap:
      return "map";
    case Kind::kBool:
      return "bool";
    case Kind::kInt:
      return "int";
    case Kind::kFloat:
      return "float";
    case Kind::kString:
      return "str";
    case Kind::kVector2:
      return "vector2";
    case Kind::kVector3:
      return "vector3";
    case Kind::kQuaternion:
      return "quaternion";
    case Kind::kMatrix3:
      return "matrix3";
    case Kind::kVector:
      return "vector";
  }
  return "unknown";
}

void Dictionary::update(const msgpack::object& message) {
  if (message.type != msgpack::type::MAP) {
    throw SpineError("message is a " + std::string(msgpack_type_name(message.type)) +
                     ", expected a map");
  }
  if (!is_map()) throw SpineError("cannot merge a message into a value");
  update_map(message, nullptr, 0);
}

void Dictionary::clear() {
  kind_ = Kind::kMap;
  children_.clear();
  string_.clear();
  array_.clear();
}

void Dictionary::update_map(const msgpack::object& message, const Path* path, int depth) {
  if (depth > kMaxDepth) throw SpineError(describe(path) + " is nested too deeply");
  const msgpack::object_map& map = message.via.map;
  for (std::uint32_t i = 0; i < map.size; ++i) {
    const msgpack::object& key = map.ptr[i].key;
    if (key.type != msgpack::type::STR) {
      throw SpineError("a key under " + describe(path) + " is a " +
                       std::string(msgpack_type_name(key.type)) + ", keys must be strings");
    }
    const std::string_view name(key.via.str.ptr, key.via.str.size);
    const Path child_path{path, name};
    auto it = children_.find(name);
    const bool fresh = it == children_.end();  // a new key takes any type
    if (fresh) it = children_.emplace(std::string(name), std::make_unique<Dictionary>()).first;
    it->second->assign(map.ptr[i].val, &child_path, depth + 1, fresh);
  }
}

void Dictionary::assign(const msgpack::object& value, const Path* path, int depth, bool fresh) {
  const Kind kind = kind_of(value, path);
  if (!fresh && kind != kind_) {
    throw SpineError(describe(path) + " changed type from " + std::string(kind_name(kind_)) +
                     " to " + std::string(kind_name(kind)));
  }
  switch (kind) {
    case Kind::kMap:
      kind_ = Kind::kMap;
      update_map(value, path, depth);
      return;
    case Kind::kBool:
      bool_ = value.via.boolean;
      break;
    case Kind::kInt:
      int_ = to_int64(value, path);
      break;
    case Kind::kFloat:
      float_ = value.via.f64;  // msgpack-cxx widens float32 into f64
      break;
    case Kind::kString:
      string_.assign(value.via.str.ptr, value.via.str.size);
      break;
    default:  // arrays
      copy_numbers(value, path, array_);
  }
  kind_ = kind;
}

bool Dictionary::has(std::string_view key) const {
  return is_map() && children_.find(key) != children_.end();
}

const Dictionary& Dictionary::at(std::string_view key) const {
  if (!is_map()) {
    throw SpineError("cannot look up '" + std::string(key) + "' in a " +
                     std::string(kind_name(kind_)));
  }
  const auto it = children_.find(key);
  if (it == children_.end()) throw SpineError("missing key '" + std::string(key) + "'");
  return *it->second;
}

bool Dictionary::as_bool() const {
  if (kind_ != Kind::kBool) {
    throw SpineError("expected a bool, found a " + std::string(kind_name(kind_)));
  }
  return bool_;
}

double Dictionary::as_number() const {
  if (kind_ == Kind::kFloat) return float_;
  if (kind_ == Kind::kInt) return static_cast<double>(int_);
  throw SpineError("expected a number, found a " + std::string(kind_name(kind_)));
}

const std::string& Dictionary::as_string() const {
  if (kind_ != Kind::kString) {
    throw SpineError("expected a string, found a " + std::string(kind_name(kind_)));
  }
  return string_;
}

const std::vector<double>& Dictionary::as_array() const {
  if (kind_ == Kind::kMap || kind_ == Kind::kBool || kind_ == Kind::kInt || kind_ == Kind::kFloat ||
      kind_ == Kind::kString) {
    throw SpineError("expected an array, found a " + std::string(kind_name(kind_)));
  }
  return array_;
}

}  // namespace upkie_rl
