#pragma once
/// @file
/// Packing a real number as msgpack float64, always.
///
/// msgpack-cxx's packer::pack_double (4.x, Debian) packs a double with an integral value
/// (0.0, 1.0, -2.0) as a msgpack *integer*. The Upkie spine types every key by its first
/// value and stops on a type change, so a velocity that goes 0.0 -> 0.5 would kill it.
/// Writing the float64 marker and bytes ourselves keeps the wire type fixed.

#include <bit>
#include <cstdint>
#include <cstring>
#include <msgpack.hpp>

namespace upkie_rl {

/// Appends `value` to `buffer` as msgpack float64 (marker 0xcb, then big-endian bytes);
/// NaN and infinities included.
inline void pack_float64(msgpack::sbuffer& buffer, double value) {
  std::uint64_t bits = std::bit_cast<std::uint64_t>(value);
  char bytes[9];
  bytes[0] = static_cast<char>(0xcb);
  for (int i = 8; i >= 1; --i) {
    bytes[i] = static_cast<char>(bits & 0xff);
    bits >>= 8;
  }
  buffer.write(bytes, sizeof(bytes));
}

}  // namespace upkie_rl
