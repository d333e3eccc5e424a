#include "sim/observation_dict.hpp"

#include <string_view>
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

}  // namespace

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
