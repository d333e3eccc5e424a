#include "view/frame_broadcaster.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "view/view_error.hpp"

namespace upkie_rl {
namespace {

std::vector<double> frame_of(double value) { return {value, -value}; }

TEST(FrameBroadcaster, CollectsTheFramesAfterTheLastOneOldestFirst) {
  FrameBroadcaster frames(2, 8);
  EXPECT_EQ(frames.newest(), 0u);
  for (int i = 1; i <= 3; ++i) frames.publish(frame_of(i));
  std::vector<double> out;
  const auto collected = frames.collect(1, 100, out);
  EXPECT_EQ(collected.newest, 3u);
  EXPECT_EQ(collected.skipped, 0u);
  EXPECT_EQ(out, (std::vector<double>{2, -2, 3, -3}));
  out.clear();
  const auto nothing = frames.collect(3, 100, out);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(nothing.newest, 3u);
}

TEST(FrameBroadcaster, AReaderARingBehindLosesTheOldestFrames) {
  FrameBroadcaster frames(2, 4);
  for (int i = 1; i <= 10; ++i) frames.publish(frame_of(i));
  std::vector<double> out;
  const auto collected = frames.collect(0, 100, out);
  EXPECT_EQ(collected.newest, 10u);
  EXPECT_EQ(collected.skipped, 6u);  // frames 1..6 were overwritten
  EXPECT_EQ(out, (std::vector<double>{7, -7, 8, -8, 9, -9, 10, -10}));
}

TEST(FrameBroadcaster, AMessageCarriesTheNewestFramesUpToItsLimit) {
  FrameBroadcaster frames(2, 16);
  for (int i = 1; i <= 10; ++i) frames.publish(frame_of(i));
  std::vector<double> out;
  const auto collected = frames.collect(2, 3, out);
  EXPECT_EQ(collected.skipped, 5u);
  EXPECT_EQ(out, (std::vector<double>{8, -8, 9, -9, 10, -10}));
}

TEST(FrameBroadcaster, RefusesFramesOfTheWrongSizeAndKeepsItsFrames) {
  FrameBroadcaster frames(2, 4);
  frames.publish(frame_of(1));
  const std::vector<double> wrong = {1.0, 2.0, 3.0};
  EXPECT_THROW(frames.publish(wrong), ViewError);
  EXPECT_EQ(frames.newest(), 1u);
  EXPECT_THROW(FrameBroadcaster(0, 4), ViewError);
  EXPECT_THROW(FrameBroadcaster(2, 0), ViewError);
}

}  // namespace
}  // namespace upkie_rl
