#include "policy/crc32c.hpp"

#include <gtest/gtest.h>

namespace upkie_rl {
namespace {

TEST(Crc32c, MatchesTheStandardCheckValue) {
  EXPECT_EQ(crc32c("123456789"), 0xE3069283u);
  EXPECT_EQ(crc32c(""), 0u);
}

TEST(Crc32c, ContinuesAcrossChunks) {
  const std::string text = "123456789";
  const auto bytes = std::as_bytes(std::span<const char>(text.data(), text.size()));
  EXPECT_EQ(crc32c(bytes.subspan(4), crc32c(bytes.first(4))), 0xE3069283u);
}

TEST(Crc32c, MaskRotatesAndAddsTheConstant) {
  // ((c >> 15) | (c << 17)) + 0xA282EAD8 computed by hand for c = 0xE3069283.
  const std::uint32_t c = 0xE3069283u;
  const std::uint32_t rotated = (c >> 15) | (c << 17);
  EXPECT_EQ(mask_crc32c(c), static_cast<std::uint32_t>(rotated + 0xA282EAD8u));
  EXPECT_EQ(mask_crc32c(0), 0xA282EAD8u);
}

}  // namespace
}  // namespace upkie_rl
