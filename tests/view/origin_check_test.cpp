#include "view/origin_check.hpp"

#include <gtest/gtest.h>

namespace upkie_rl {
namespace {

TEST(OriginCheck, TheViewersOwnPageAndNonBrowsersAreAccepted) {
  EXPECT_TRUE(is_same_origin("http://127.0.0.1:7000", "127.0.0.1:7000"));
  EXPECT_TRUE(is_same_origin("http://localhost:7000", "localhost:7000"));  // an SSH tunnel
  EXPECT_TRUE(is_same_origin("HTTP://LocalHost:7000", "localhost:7000"));
  EXPECT_TRUE(is_same_origin("https://robot.lan:8443", "robot.lan:8443"));
  EXPECT_TRUE(is_same_origin("", "127.0.0.1:7000"));  // no Origin: not a browser
}

TEST(OriginCheck, PagesOfOtherSitesAreRefused) {
  EXPECT_FALSE(is_same_origin("http://evil.example", "127.0.0.1:7000"));
  EXPECT_FALSE(is_same_origin("http://127.0.0.1:8000", "127.0.0.1:7000"));  // another port
  EXPECT_FALSE(is_same_origin("http://127.0.0.1:7000.evil.example", "127.0.0.1:7000"));
  EXPECT_FALSE(is_same_origin("null", "127.0.0.1:7000"));  // a file or sandboxed page
  EXPECT_FALSE(is_same_origin("ws://127.0.0.1:7000", "127.0.0.1:7000"));
  EXPECT_FALSE(is_same_origin("http://", ""));
  EXPECT_FALSE(is_same_origin("http://127.0.0.1:7000", ""));  // no Host to compare with
}

TEST(HostCheck, LoopbackNamesReachALoopbackServer) {
  EXPECT_TRUE(is_allowed_host("127.0.0.1:7000", true));
  EXPECT_TRUE(is_allowed_host("127.0.0.2", true));
  EXPECT_TRUE(is_allowed_host("LocalHost:7000", true));
  EXPECT_TRUE(is_allowed_host("[::1]:7000", true));
  EXPECT_TRUE(is_allowed_host("", true));  // no Host: not a browser
}

TEST(HostCheck, OtherNamesAreRefusedOnLoopbackOnly) {
  // A page whose own name was made to resolve to 127.0.0.1 (DNS rebinding).
  EXPECT_FALSE(is_allowed_host("evil.example:7000", true));
  EXPECT_FALSE(is_allowed_host("localhost.evil.example:7000", true));
  EXPECT_FALSE(is_allowed_host("192.168.1.5:7000", true));
  EXPECT_FALSE(is_allowed_host("[::1", true));
  EXPECT_FALSE(is_allowed_host("[fe80::1]:7000", true));
  EXPECT_TRUE(is_allowed_host("robot.lan:7000", false));  // --host 0.0.0.0: open on purpose
}

}  // namespace
}  // namespace upkie_rl
