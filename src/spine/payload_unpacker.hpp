#pragma once
/// @file
/// Decoding one msgpack payload of the spine link, with limits, into reusable memory.

#include <cstddef>
#include <msgpack.hpp>
#include <span>
#include <vector>

namespace upkie_rl {

/// Unpacks a payload into a msgpack object tree (msgpack-cxx's msgpack::object, decoded
/// by our own parser: msgpack-cxx's unpack allocates parser stacks at every call). The
/// bytes are first copied out of the shared memory (the other side may write it
/// concurrently) into a buffer reserved once, and the tree lives in a zone that is
/// cleared and reused: once warmed up, decoding a message of the usual size allocates
/// nothing. Strings point into the copied bytes. The tree is valid until the next call.
class PayloadUnpacker {
 public:
  /// Limits on any one message (containers, strings, nesting).
  static constexpr std::size_t kMaxContainerSize = 1024;
  static constexpr std::size_t kMaxDepth = 32;

  /// @param max_payload_size Largest payload accepted [bytes].
  explicit PayloadUnpacker(std::size_t max_payload_size = std::size_t{1} << 20);

  /// Decodes exactly one msgpack object spanning all of `bytes`.
  /// @throws SpineError on an empty, truncated, malformed or oversized payload, on
  ///         trailing bytes, or when a limit is exceeded (containers of more than
  ///         kMaxContainerSize elements or of more elements than bytes left, nesting
  ///         deeper than kMaxDepth).
  const msgpack::object& unpack(std::span<const char> bytes);

 private:
  std::size_t max_payload_size_;
  std::vector<char> bytes_;
  msgpack::zone zone_;
  msgpack::object object_;
};

}  // namespace upkie_rl
