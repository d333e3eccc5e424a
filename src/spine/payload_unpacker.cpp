#include "spine/payload_unpacker.hpp"

#include <bit>
#include <cstring>
#include <string>

#include "spine/spine_error.hpp"

namespace upkie_rl {
namespace {

constexpr std::size_t kZoneChunkSize = std::size_t{64} * 1024;

/// A recursive-descent msgpack decoder building msgpack::object trees in a zone, with
/// strings and binaries pointing into the decoded bytes. msgpack-cxx's own unpack
/// allocates its parser stacks at every call; this one allocates only from the zone.
/// A container's declared size is checked against the bytes left before anything is
/// allocated for it, so a hostile size cannot reserve more than ~48 bytes per payload byte.
class Decoder {
 public:
  Decoder(const char* data, std::size_t size, msgpack::zone& zone, std::size_t max_container,
          std::size_t max_depth)
      : data_(reinterpret_cast<const unsigned char*>(data)),
        size_(size),
        zone_(zone),
        max_container_(max_container),
        max_depth_(max_depth) {}

  // Over 60 lines on purpose: one case per msgpack marker byte, a dispatch table read side
  // by side with the format's specification; split, the table would be scattered.
  void decode(msgpack::object& out, std::size_t depth) {
    if (depth > max_depth_) {
      throw SpineError("msgpack payload nested deeper than " + std::to_string(max_depth_));
    }
    const unsigned char marker = take(1)[0];
    if (marker <= 0x7f) return set_unsigned(out, marker);
    if (marker >= 0xe0) return set_signed(out, static_cast<std::int8_t>(marker));
    if (marker >= 0x80 && marker <= 0x8f) return decode_map(out, marker & 0x0f, depth);
    if (marker >= 0x90 && marker <= 0x9f) return decode_array(out, marker & 0x0f, depth);
    if (marker >= 0xa0 && marker <= 0xbf) return set_bytes(out, msgpack::type::STR, marker & 0x1f);
    switch (marker) {
      case 0xc0:
        out.type = msgpack::type::NIL;
        return;
      case 0xc2:
      case 0xc3:
        out.type = msgpack::type::BOOLEAN;
        out.via.boolean = marker == 0xc3;
        return;
      case 0xc4:
        return set_bytes(out, msgpack::type::BIN, big_endian(1));
      case 0xc5:
        return set_bytes(out, msgpack::type::BIN, big_endian(2));
      case 0xc6:
        return set_bytes(out, msgpack::type::BIN, big_endian(4));
      case 0xc7:
        return set_ext(out, big_endian(1));
      case 0xc8:
        return set_ext(out, big_endian(2));
      case 0xc9:
        return set_ext(out, big_endian(4));
      case 0xca:
        out.type = msgpack::type::FLOAT32;
        out.via.f64 = std::bit_cast<float>(static_cast<std::uint32_t>(big_endian(4)));
        return;
      case 0xcb:
        out.type = msgpack::type::FLOAT64;
        out.via.f64 = std::bit_cast<double>(big_endian(8));
        return;
      case 0xcc:
        return set_unsigned(out, big_endian(1));
      case 0xcd:
        return set_unsigned(out, big_endian(2));
      case 0xce:
        return set_unsigned(out, big_endian(4));
      case 0xcf:
        return set_unsigned(out, big_endian(8));
      case 0xd0:
        return set_signed(out, static_cast<std::int8_t>(big_endian(1)));
      case 0xd1:
        return set_signed(out, static_cast<std::int16_t>(big_endian(2)));
      case 0xd2:
        return set_signed(out, static_cast<std::int32_t>(big_endian(4)));
      case 0xd3:
        return set_signed(out, static_cast<std::int64_t>(big_endian(8)));
      case 0xd4:
        return set_ext(out, 1);
      case 0xd5:
        return set_ext(out, 2);
      case 0xd6:
        return set_ext(out, 4);
      case 0xd7:
        return set_ext(out, 8);
      case 0xd8:
        return set_ext(out, 16);
      case 0xd9:
        return set_bytes(out, msgpack::type::STR, big_endian(1));
      case 0xda:
        return set_bytes(out, msgpack::type::STR, big_endian(2));
      case 0xdb:
        return set_bytes(out, msgpack::type::STR, big_endian(4));
      case 0xdc:
        return decode_array(out, big_endian(2), depth);
      case 0xdd:
        return decode_array(out, big_endian(4), depth);
      case 0xde:
        return decode_map(out, big_endian(2), depth);
      case 0xdf:
        return decode_map(out, big_endian(4), depth);
      default:  // 0xc1 is never used
        throw SpineError("malformed msgpack payload: invalid marker byte 0xc1 at offset " +
                         std::to_string(offset_ - 1));
    }
  }

  std::size_t offset() const { return offset_; }

 private:
  const unsigned char* take(std::size_t count) {
    if (count > size_ - offset_) {
      throw SpineError("truncated msgpack payload (" + std::to_string(size_) + " bytes)");
    }
    const unsigned char* bytes = data_ + offset_;
    offset_ += count;
    return bytes;
  }

  std::uint64_t big_endian(std::size_t count) {
    const unsigned char* bytes = take(count);
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < count; ++i) value = (value << 8) | bytes[i];
    return value;
  }

  static void set_unsigned(msgpack::object& out, std::uint64_t value) {
    out.type = msgpack::type::POSITIVE_INTEGER;
    out.via.u64 = value;
  }

  static void set_signed(msgpack::object& out, std::int64_t value) {
    if (value >= 0) return set_unsigned(out, static_cast<std::uint64_t>(value));
    out.type = msgpack::type::NEGATIVE_INTEGER;
    out.via.i64 = value;
  }

  void set_bytes(msgpack::object& out, msgpack::type::object_type type, std::uint64_t size) {
    const char* bytes = reinterpret_cast<const char*>(take(size));
    out.type = type;
    if (type == msgpack::type::STR) {
      out.via.str.size = static_cast<std::uint32_t>(size);
      out.via.str.ptr = bytes;
    } else {
      out.via.bin.size = static_cast<std::uint32_t>(size);
      out.via.bin.ptr = bytes;
    }
  }

  void set_ext(msgpack::object& out, std::uint64_t size) {
    // Type byte then data; msgpack-cxx's object_ext points at the type byte.
    const char* bytes = reinterpret_cast<const char*>(take(size + 1));
    out.type = msgpack::type::EXT;
    out.via.ext.size = static_cast<std::uint32_t>(size);
    out.via.ext.ptr = bytes;
  }

  /// Checks a declared container size before allocating for it.
  void check_size(std::uint64_t count, std::size_t min_bytes_each) {
    if (count > max_container_) {
      throw SpineError("msgpack payload exceeds a size limit: a container of " +
                       std::to_string(count) + " elements (at most " +
                       std::to_string(max_container_) + ")");
    }
    if (count * min_bytes_each > size_ - offset_) {
      throw SpineError("truncated msgpack payload (" + std::to_string(size_) +
                       " bytes): a container declares " + std::to_string(count) + " elements");
    }
  }

  void decode_array(msgpack::object& out, std::uint64_t count, std::size_t depth) {
    check_size(count, 1);
    auto* elements = count == 0 ? nullptr
                                : static_cast<msgpack::object*>(zone_.allocate_align(
                                      count * sizeof(msgpack::object), alignof(msgpack::object)));
    out.type = msgpack::type::ARRAY;
    out.via.array.size = static_cast<std::uint32_t>(count);
    out.via.array.ptr = elements;
    for (std::uint64_t i = 0; i < count; ++i) decode(elements[i], depth + 1);
  }

  void decode_map(msgpack::object& out, std::uint64_t count, std::size_t depth) {
    check_size(count, 2);
    auto* pairs = count == 0
                      ? nullptr
                      : static_cast<msgpack::object_kv*>(zone_.allocate_align(
                            count * sizeof(msgpack::object_kv), alignof(msgpack::object_kv)));
    out.type = msgpack::type::MAP;
    out.via.map.size = static_cast<std::uint32_t>(count);
    out.via.map.ptr = pairs;
    for (std::uint64_t i = 0; i < count; ++i) {
      decode(pairs[i].key, depth + 1);
      decode(pairs[i].val, depth + 1);
    }
  }

  const unsigned char* data_;
  std::size_t size_;
  std::size_t offset_ = 0;
  msgpack::zone& zone_;
  std::size_t max_container_;
  std::size_t max_depth_;
};

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
  Decoder decoder(bytes_.data(), bytes_.size(), zone_, kMaxContainerSize, kMaxDepth);
  try {
    decoder.decode(object_, 0);
  } catch (const std::bad_alloc&) {
    throw SpineError("msgpack payload too large to decode");
  }
  if (decoder.offset() != bytes_.size()) {
    throw SpineError("msgpack payload has " + std::to_string(bytes_.size() - decoder.offset()) +
                     " trailing bytes after one object");
  }
  return object_;
}

}  // namespace upkie_rl
