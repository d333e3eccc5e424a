#include "spine/payload_unpacker.hpp"

#include <string>

#include "spine/spine_error.hpp"

namespace upkie_rl {
namespace {

/// Strings and binaries reference the copied bytes instead of being copied again.
bool reference_everything(msgpack::type::object_type, std::size_t, void*) { return true; }

constexpr std::size_t kZoneChunkSize = 64 * 1024;

}  // namespace

PayloadUnpacker::PayloadUnpacker(std::size_t max_payload_size)
    : max_payload_size_(max_payload_size), zone_(kZoneChunkSize) {
  bytes_.reserve(max_payload_size);
}

const msgpack::object& PayloadUnpacker::unpack(std::span<const char> bytes) {
  if (bytes.empty()) throw SpineError("empty msgpack payload");
  if (bytes.size() > max_payload_size_) {
    throw SpineError("payload of " + std::to_string(bytes.size()) + " bytes exceeds the " +
                     std::to_string(max_payload_size_) + "-byte limit");
  }
  bytes_.assign(bytes.begin(), bytes.end());
  zone_.clear();
  const msgpack::unpack_limit limit(kMaxContainerSize, kMaxContainerSize, max_payload_size_,
                                    max_payload_size_, max_payload_size_, kMaxDepth);
  std::size_t offset = 0;
  bool referenced = false;
  try {
    object_ = msgpack::unpack(zone_, bytes_.data(), bytes_.size(), offset, referenced,
                              &reference_everything, nullptr, limit);
  } catch (const msgpack::insufficient_bytes&) {
    throw SpineError("truncated msgpack payload (" + std::to_string(bytes.size()) + " bytes)");
  } catch (const msgpack::depth_size_overflow&) {
    throw SpineError("msgpack payload nested deeper than " + std::to_string(kMaxDepth));
  } catch (const msgpack::size_overflow& error) {
    throw SpineError(std::string("msgpack payload exceeds a size limit: ") + error.what());
  } catch (const msgpack::unpack_error& error) {
    throw SpineError(std::string("malformed msgpack payload: ") + error.what());
  } catch (const std::bad_alloc&) {
    throw SpineError("msgpack payload too large to decode");
  }
  if (offset != bytes_.size()) {
    throw SpineError("msgpack payload has " + std::to_string(bytes_.size() - offset) +
                     " trailing bytes after one object");
  }
  return object_;
}

}  // namespace upkie_rl
