/// @file
/// libFuzzer target: every message decoding path of the spine link. Each input is taken
/// as a shared-memory payload and decoded as the spine decodes a Start configuration and
/// an Action (merged into a dictionary holding the default action, so that type changes
/// are exercised), and as an agent decodes an observation. Refusing an input with a
/// SpineError is the expected outcome; anything else (a crash, an ASan report, another
/// exception, a leak) is a bug. Differential check: whatever our msgpack decoder accepts,
/// msgpack-cxx's decodes to the same tree.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "sim/observation.hpp"
#include "spine/dictionary.hpp"
#include "spine/observation_reader.hpp"
#include "spine/payload_unpacker.hpp"
#include "spine/reset_config.hpp"
#include "spine/servo_action_message.hpp"
#include "spine/spine_error.hpp"

namespace {

using upkie_rl::Dictionary;
using upkie_rl::SpineError;

constexpr std::array<double, upkie_rl::kNumServos> kEfforts = {16.0, 16.0, 1.7, 16.0, 16.0, 1.7};

/// Structural equality with reals compared bit for bit (NaN equals itself).
bool same(const msgpack::object& a, const msgpack::object& b) {
  if (a.type != b.type) return false;
  switch (a.type) {
    case msgpack::type::FLOAT32:
    case msgpack::type::FLOAT64:
      return std::bit_cast<std::uint64_t>(a.via.f64) == std::bit_cast<std::uint64_t>(b.via.f64);
    case msgpack::type::ARRAY:
      if (a.via.array.size != b.via.array.size) return false;
      for (std::uint32_t i = 0; i < a.via.array.size; ++i) {
        if (!same(a.via.array.ptr[i], b.via.array.ptr[i])) return false;
      }
      return true;
    case msgpack::type::MAP:
      if (a.via.map.size != b.via.map.size) return false;
      for (std::uint32_t i = 0; i < a.via.map.size; ++i) {
        if (!same(a.via.map.ptr[i].key, b.via.map.ptr[i].key) ||
            !same(a.via.map.ptr[i].val, b.via.map.ptr[i].val)) {
          return false;
        }
      }
      return true;
    // msgpack-cxx's operator== compares strings with memcmp even when they are empty, and
    // its own decoder leaves an empty string's pointer null: UBSan's nonnull-attribute
    // report on (0xa0). std::string_view compares nothing when the size is zero.
    case msgpack::type::STR:
      return std::string_view(a.via.str.ptr, a.via.str.size) ==
             std::string_view(b.via.str.ptr, b.via.str.size);
    case msgpack::type::BIN:
      return std::string_view(a.via.bin.ptr, a.via.bin.size) ==
             std::string_view(b.via.bin.ptr, b.via.bin.size);
    default:
      return a == b;
  }
}

void decode_as_configuration(const msgpack::object& object) {
  Dictionary configuration;
  try {
    configuration.update(object);
    upkie_rl::reset_state_from_config(configuration);
  } catch (const SpineError&) {
  }
}

void decode_as_action(const msgpack::object& object, const msgpack::object& defaults) {
  Dictionary action_dictionary;
  action_dictionary.update(defaults);
  upkie_rl::ServoAction action = upkie_rl::spine_default_servo_action();
  try {
    action_dictionary.update(object);
    upkie_rl::read_servo_action(action_dictionary, action, &kEfforts);
  } catch (const SpineError&) {
  }
}

void decode_as_observation(const msgpack::object& object) {
  upkie_rl::Observation observation;
  try {
    upkie_rl::read_observation(object, observation);
  } catch (const SpineError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // The default action message, decoded once (its own unpacker keeps it alive).
  static msgpack::sbuffer default_message = [] {
    msgpack::sbuffer buffer;
    upkie_rl::write_servo_action_msgpack(upkie_rl::spine_default_servo_action(), buffer);
    return buffer;
  }();
  static upkie_rl::PayloadUnpacker default_unpacker;
  static const msgpack::object& defaults =
      default_unpacker.unpack({default_message.data(), default_message.size()});
  static upkie_rl::PayloadUnpacker unpacker;  // reused, as by the spine and the agent

  const msgpack::object* object = nullptr;
  try {
    object = &unpacker.unpack({reinterpret_cast<const char*>(data), size});
  } catch (const SpineError&) {
    return 0;
  }
  // Differential: msgpack-cxx (same limits) must decode what we accepted to the same tree.
  try {
    const std::size_t limit = upkie_rl::PayloadUnpacker::kMaxContainerSize;
    const msgpack::unpack_limit limits(limit, limit, size, size, size,
                                       upkie_rl::PayloadUnpacker::kMaxDepth + 1);
    std::size_t offset = 0;
    const msgpack::object_handle reference = msgpack::unpack(
        reinterpret_cast<const char*>(data), size, offset, nullptr, nullptr, limits);
    if (offset != size || !same(reference.get(), *object)) std::abort();
  } catch (const msgpack::unpack_error&) {
    std::abort();
  }
  decode_as_configuration(*object);
  decode_as_action(*object, defaults);
  decode_as_observation(*object);
  return 0;
}
