#include "sim/observation_dict.hpp"

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sim/msgpack_float64.hpp"
#include "sim/observation_walk.hpp"

namespace upkie_rl {
namespace {

/// Packs msgpack directly (packer writes through to the buffer, so raw float64 bytes can
/// be interleaved with packer calls).
class MsgpackWriter {
 public:
  explicit MsgpackWriter(msgpack::sbuffer& buffer) : buffer_(buffer), packer_(buffer) {}
  void begin_map(std::size_t size) { packer_.pack_map(static_cast<uint32_t>(size)); }
  void end_map() {}
  void key(std::string_view key) {
    packer_.pack_str(static_cast<uint32_t>(key.size()));
    packer_.pack_str_body(key.data(), static_cast<uint32_t>(key.size()));
  }
  void real(double value) { pack_float64(buffer_, value); }
  void boolean(bool value) { value ? packer_.pack_true() : packer_.pack_false(); }
  void integer(int value) { packer_.pack_int(value); }
  void reals(const double* values, std::size_t size) {
    packer_.pack_array(static_cast<uint32_t>(size));
    for (std::size_t i = 0; i < size; ++i) pack_float64(buffer_, values[i]);
  }

 private:
  msgpack::sbuffer& buffer_;
  msgpack::packer<msgpack::sbuffer> packer_;
};

/// Builds a nlohmann::json tree with a stack of open objects.
class JsonWriter {
 public:
  JsonWriter() { stack_.reserve(8); }
  void begin_map(std::size_t) {
    nlohmann::json& map = slot();
    map = nlohmann::json::object();
    stack_.push_back(&map);
  }
  void end_map() { stack_.pop_back(); }
  void key(std::string_view key) { key_ = key; }
  void real(double value) { slot() = value; }
  void boolean(bool value) { slot() = value; }
  void integer(int value) { slot() = value; }
  void reals(const double* values, std::size_t size) {
    slot() = std::vector<double>(values, values + size);
  }
  nlohmann::json& root() { return root_; }

 private:
  nlohmann::json& slot() { return stack_.empty() ? root_ : (*stack_.back())[std::string(key_)]; }
  nlohmann::json root_;
  std::vector<nlohmann::json*> stack_;
  std::string_view key_;
};

/// Lists the declaration's keys with their dotted paths.
class KeyLister {
 public:
  KeyLister(std::vector<ObservationKey>& keys, std::string prefix)
      : keys_(keys), prefix_(std::move(prefix)) {}
  template <typename Children>
  void map(std::string_view key, KeyPresence presence, Children&& children) {
    add(key, true, false, presence);
    KeyLister fields(keys_, prefix_ + std::string(key) + ".");
    children(fields);
  }
  template <typename Children>
  void map_if(std::string_view key, bool&, Children&& children) {
    map(key, KeyPresence::kOptional, children);
  }
  template <typename Field>
  void real(std::string_view key, Field&, KeyPresence presence) {
    add(key, false, false, presence);
  }
  template <typename Field>
  void boolean(std::string_view key, Field&, KeyPresence presence) {
    add(key, false, false, presence);
  }
  template <typename Field>
  void vector3(std::string_view key, Field&, KeyPresence presence) {
    add(key, false, false, presence);
  }
  template <typename Field>
  void quaternion(std::string_view key, Field&, KeyPresence presence) {
    add(key, false, false, presence);
  }
  template <typename Field>
  void matrix3(std::string_view key, Field&, KeyPresence presence) {
    add(key, false, false, presence);
  }
  template <typename Value>
  void computed(std::string_view key, Value&&) {
    add(key, false, true, KeyPresence::kOptional);
  }

 private:
  void add(std::string_view key, bool is_map, bool computed, KeyPresence presence) {
    keys_.push_back(
        {prefix_ + std::string(key), is_map, computed, presence == KeyPresence::kRequired});
  }
  std::vector<ObservationKey>& keys_;
  std::string prefix_;
};

}  // namespace

std::vector<ObservationKey> observation_keys() {
  std::vector<ObservationKey> keys;
  Observation observation;
  KeyLister lister(keys, "");
  visit_observation_fields(observation, lister);
  return keys;
}

nlohmann::json observation_to_json(const Observation& observation) {
  JsonWriter writer;
  walk_observation(observation, writer);
  return std::move(writer.root());
}

void pack_observation(const Observation& observation, msgpack::sbuffer& buffer) {
  MsgpackWriter writer(buffer);
  walk_observation(observation, writer);
}

void write_observation_msgpack(const Observation& observation, msgpack::sbuffer& buffer) {
  buffer.clear();
  pack_observation(observation, buffer);
}

}  // namespace upkie_rl
