#include "rl/logging/tensorboard_writer.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

namespace upkie_rl {
namespace {

std::filesystem::path fresh_directory(const std::string& name) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("upkie_rl_tb_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(path);
  return path;
}

TEST(TensorBoardWriter, RecordsDecodeWithTheirCrcs) {
  const auto directory = fresh_directory("decode");
  std::filesystem::path path;
  {
    TensorBoardWriter writer(directory);
    path = writer.path();
    const std::vector<ScalarValue> first{{"train/loss", 0.25f}, {"train/approx_kl", 0.01f}};
    writer.add_scalars(2040, first, 1700000000.5);
    const std::vector<ScalarValue> second{{"rollout/ep_rew_mean", -3.5f}};
    writer.add_scalars(4080, second, 1700000001.0);
    writer.flush();
  }
  EXPECT_NE(path.filename().string().find("tfevents"), std::string::npos);
  const std::vector<TensorBoardEvent> events = read_event_file(path);
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].file_version, "brain.Event:2");
  EXPECT_EQ(events[1].step, 2040);
  EXPECT_DOUBLE_EQ(events[1].wall_time, 1700000000.5);
  ASSERT_EQ(events[1].scalars.size(), 2u);
  EXPECT_EQ(events[1].scalars[0].tag, "train/loss");
  EXPECT_FLOAT_EQ(events[1].scalars[0].value, 0.25f);
  EXPECT_EQ(events[1].scalars[1].tag, "train/approx_kl");
  EXPECT_FLOAT_EQ(events[1].scalars[1].value, 0.01f);
  EXPECT_EQ(events[2].step, 4080);
  EXPECT_EQ(events[2].scalars.at(0).tag, "rollout/ep_rew_mean");
  EXPECT_FLOAT_EQ(events[2].scalars.at(0).value, -3.5f);
  std::filesystem::remove_all(directory);
}

TEST(TensorBoardWriter, EncodesTheProtobufFieldsByHand) {
  TensorBoardEvent event;
  event.wall_time = 0.0;
  event.step = 1;
  event.scalars = {{"a", 1.0f}};
  const std::string bytes = encode_event(event);
  // wall_time: tag 0x09 + 8 bytes; step: 0x10 0x01; summary: 0x2A len, value: 0x0A len,
  // tag: 0x0A 0x01 'a', simple_value: 0x15 + float 1.0 (00 00 80 3F).
  const std::string expected = std::string("\x09", 1) + std::string(8, '\0') +
                               std::string(
                                   "\x10\x01\x2A\x0A\x0A\x08\x0A\x01"
                                   "a"
                                   "\x15",
                                   10) +
                               std::string("\x00\x00\x80\x3F", 4);
  EXPECT_EQ(bytes, expected);
}

TEST(TensorBoardWriter, CorruptedOrTruncatedFilesAreRejected) {
  const auto directory = fresh_directory("corrupt");
  std::filesystem::path path;
  {
    TensorBoardWriter writer(directory);
    path = writer.path();
    const std::vector<ScalarValue> scalars{{"train/loss", 1.0f}};
    writer.add_scalars(1, scalars, 1.0);
  }
  std::string bytes;
  {
    std::ifstream file(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
  }
  std::string corrupted = bytes;
  corrupted[corrupted.size() - 6] ^= 0x01;
  std::ofstream(path, std::ios::binary | std::ios::trunc) << corrupted;
  EXPECT_THROW(read_event_file(path), std::runtime_error);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() - 3);
  try {
    read_event_file(path);
    FAIL() << "a truncated file must be rejected";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("truncated"), std::string::npos) << error.what();
  }
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace upkie_rl
