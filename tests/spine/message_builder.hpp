#pragma once
/// @file
/// Builds msgpack messages byte by byte for tests, including ones a well-behaved agent
/// would never send.

#include <msgpack.hpp>
#include <string>
#include <string_view>

#include "sim/msgpack_float64.hpp"

namespace upkie_rl::testing {

class MessageBuilder {
 public:
  MessageBuilder() = default;
  MessageBuilder(MessageBuilder&&) = default;
  MessageBuilder& map(std::uint32_t size) {
    packer().pack_map(size);
    return *this;
  }
  MessageBuilder& array(std::uint32_t size) {
    packer().pack_array(size);
    return *this;
  }
  MessageBuilder& key(std::string_view key) {
    packer().pack_str(static_cast<std::uint32_t>(key.size()));
    packer().pack_str_body(key.data(), static_cast<std::uint32_t>(key.size()));
    return *this;
  }
  MessageBuilder& real(double value) {
    pack_float64(buffer_, value);
    return *this;
  }
  MessageBuilder& real32(float value) {
    packer().pack_float(value);
    return *this;
  }
  MessageBuilder& integer(long value) {
    packer().pack_int64(value);
    return *this;
  }
  MessageBuilder& boolean(bool value) {
    value ? packer().pack_true() : packer().pack_false();
    return *this;
  }
  MessageBuilder& nil() {
    packer().pack_nil();
    return *this;
  }
  MessageBuilder& binary(std::string_view bytes) {
    packer().pack_bin(static_cast<std::uint32_t>(bytes.size()));
    packer().pack_bin_body(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
    return *this;
  }
  MessageBuilder& string(std::string_view text) { return key(text); }

  std::string bytes() const { return std::string(buffer_.data(), buffer_.size()); }
  const msgpack::object_handle& object() {
    handle_ = msgpack::unpack(buffer_.data(), buffer_.size());
    return handle_;
  }

 private:
  msgpack::packer<msgpack::sbuffer> packer() { return msgpack::packer<msgpack::sbuffer>(buffer_); }
  msgpack::sbuffer buffer_;
  msgpack::object_handle handle_;
};

/// {"servo": {joint: {field: value}}}.
inline MessageBuilder servo_field(std::string_view joint, std::string_view field) {
  MessageBuilder builder;
  builder.map(1).key("servo").map(1).key(joint).map(1).key(field);
  return builder;
}

}  // namespace upkie_rl::testing
