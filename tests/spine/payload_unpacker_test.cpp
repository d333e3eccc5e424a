#include "spine/payload_unpacker.hpp"

#include <gtest/gtest.h>

#include "message_builder.hpp"
#include "spine/spine_error.hpp"

namespace upkie_rl {
namespace {

using testing::MessageBuilder;

std::span<const char> span_of(const std::string& bytes) { return {bytes.data(), bytes.size()}; }

TEST(PayloadUnpacker, DecodesOneObject) {
  PayloadUnpacker unpacker;
  MessageBuilder message;
  message.map(1).key("x").real(0.5);
  const std::string bytes = message.bytes();
  const msgpack::object& object = unpacker.unpack(span_of(bytes));
  ASSERT_EQ(object.type, msgpack::type::MAP);
  EXPECT_DOUBLE_EQ(object.via.map.ptr[0].val.via.f64, 0.5);
}

TEST(PayloadUnpacker, RefusesBrokenPayloads) {
  PayloadUnpacker unpacker(1024);
  EXPECT_THROW(unpacker.unpack({}), SpineError);
  MessageBuilder message;
  message.map(2).key("x").real(0.5).key("y").real(1.5);
  const std::string bytes = message.bytes();
  EXPECT_THROW(unpacker.unpack(span_of(bytes.substr(0, bytes.size() - 3))), SpineError);
  EXPECT_THROW(unpacker.unpack(span_of(bytes + "\xc0")), SpineError);             // trailing nil
  EXPECT_THROW(unpacker.unpack(span_of(std::string("\xc1", 1))), SpineError);     // never used
  EXPECT_THROW(unpacker.unpack(span_of(std::string(2000, '\x90'))), SpineError);  // > limit
}

TEST(PayloadUnpacker, EnforcesLimits) {
  PayloadUnpacker unpacker;
  // 40 nested arrays: deeper than the limit.
  const std::string deep = std::string(40, '\x91') + '\x01';
  EXPECT_THROW(unpacker.unpack(span_of(deep)), SpineError);
  // An array that claims 2^32 - 1 elements must be refused before allocating them.
  const std::string huge("\xdd\xff\xff\xff\xff", 5);
  try {
    unpacker.unpack(span_of(huge));
    FAIL();
  } catch (const SpineError& error) {
    EXPECT_NE(std::string(error.what()).find("limit"), std::string::npos) << error.what();
  }
  // Still usable afterwards.
  MessageBuilder message;
  message.map(0);
  EXPECT_EQ(unpacker.unpack(span_of(message.bytes())).type, msgpack::type::MAP);
}

}  // namespace
}  // namespace upkie_rl
