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

namespace upkie_rl {
namespace {

/// Our decoder agrees with msgpack-cxx's on every format family.
TEST(PayloadUnpacker, AgreesWithMsgpackCxx) {
  msgpack::sbuffer buffer;
  msgpack::packer<msgpack::sbuffer> packer(buffer);
  packer.pack_map(3);
  packer.pack(std::string("ints"));
  packer.pack_array(14);
  for (std::int64_t value : {0L, 1L, 127L, 128L, 255L, 65535L, 65536L, 4294967296L, -1L, -32L, -33L,
                             -129L, -40000L, -5000000000L}) {
    packer.pack_int64(value);
  }
  packer.pack(std::string("reals and more"));
  packer.pack_array(10);
  packer.pack_float(0.25f);
  packer.pack_double(-1.5e300);
  packer.pack_nil();
  packer.pack_true();
  packer.pack_false();
  packer.pack(std::string(40, 's'));   // str8
  packer.pack(std::string(300, 'S'));  // str16
  packer.pack_bin(3);
  packer.pack_bin_body("abc", 3);
  packer.pack_ext(5, 7);
  packer.pack_ext_body("12345", 5);
  packer.pack_ext(4, -2);  // fixext4
  packer.pack_ext_body("wxyz", 4);
  packer.pack(std::string("big"));
  packer.pack_array(20);  // array16
  for (int i = 0; i < 20; ++i) {
    packer.pack_map(1);
    packer.pack(std::to_string(i));
    packer.pack_uint64(std::uint64_t{1} << 63);
  }
  const msgpack::object_handle expected = msgpack::unpack(buffer.data(), buffer.size());
  PayloadUnpacker unpacker;
  const msgpack::object& actual = unpacker.unpack({buffer.data(), buffer.size()});
  EXPECT_TRUE(actual == expected.get());
  EXPECT_EQ(actual.via.map.ptr[1].val.via.array.ptr[0].type, msgpack::type::FLOAT32);
  EXPECT_EQ(actual.via.map.ptr[1].val.via.array.ptr[8].via.ext.type(), 7);
  EXPECT_EQ(std::string(actual.via.map.ptr[1].val.via.array.ptr[9].via.ext.data(), 4), "wxyz");
}

TEST(PayloadUnpacker, RefusesContainersLargerThanThePayload) {
  PayloadUnpacker unpacker;
  // A map16 of 1000 pairs in 3 bytes: refused before anything is allocated for it.
  const std::string lie("\xde\x03\xe8", 3);
  try {
    unpacker.unpack(span_of(lie));
    FAIL();
  } catch (const SpineError& error) {
    EXPECT_NE(std::string(error.what()).find("declares 1000 elements"), std::string::npos);
  }
}

}  // namespace
}  // namespace upkie_rl
