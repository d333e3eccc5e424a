#include "render/video_writer.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "common/shell_output.hpp"
#include "common/temp_files.hpp"
#include "render/render_error.hpp"

namespace upkie_rl {
namespace {

using testing::shell_output;
using testing::temp_path;

/// Frames of a square moving across a 64x48 image.
void write_frames(VideoWriter& writer, int count) {
  std::vector<std::uint8_t> frame(64 * 48 * 3);
  for (int i = 0; i < count; ++i) {
    std::fill(frame.begin(), frame.end(), 40);
    for (int y = 10; y < 30; ++y) {
      for (int x = i % 40; x < i % 40 + 20; ++x) frame[(y * 64 + x) * 3] = 250;
    }
    writer.write(frame);
  }
}

TEST(VideoWriter, Mp4HasTheFramesAndDuration) {
  const auto path = temp_path("clip.mp4");
  {
    VideoWriter writer(path, 64, 48, 30);
    write_frames(writer, 60);
    writer.close();
    EXPECT_EQ(writer.frames(), 60);
  }
  const std::string probe = shell_output(
      "ffprobe -v error -select_streams v:0 -count_frames -show_entries "
      "stream=codec_name,pix_fmt,nb_read_frames -show_entries "
      "format=duration -of default=noprint_wrappers=1 " +
      path.string());
  EXPECT_NE(probe.find("codec_name=h264"), std::string::npos) << probe;
  EXPECT_NE(probe.find("pix_fmt=yuv420p"), std::string::npos) << probe;
  EXPECT_NE(probe.find("nb_read_frames=60"), std::string::npos) << probe;
  EXPECT_NE(probe.find("duration=2.0"), std::string::npos) << probe;
  std::filesystem::remove(path);
}

TEST(VideoWriter, GifIsWritten) {
  const auto path = temp_path("clip.gif");
  {
    VideoWriter writer(path, 64, 48, 30);
    write_frames(writer, 15);
    writer.close();
  }
  const std::string probe = shell_output(
      "ffprobe -v error -count_frames -show_entries "
      "stream=codec_name,nb_read_frames -of default=noprint_wrappers=1 " +
      path.string());
  EXPECT_NE(probe.find("codec_name=gif"), std::string::npos) << probe;
  EXPECT_NE(probe.find("nb_read_frames=15"), std::string::npos) << probe;
  std::filesystem::remove(path);
}

TEST(VideoWriter, BadPathsAreRefusedBeforeEncoding) {
  EXPECT_THROW(VideoWriter::check_path(temp_path("clip.avi")), RenderError);
  EXPECT_THROW(VideoWriter::check_path(temp_path("clip")), RenderError);
  EXPECT_THROW(VideoWriter::check_path("/nonexistent_directory_upkie/clip.mp4"), RenderError);
  EXPECT_THROW(
      VideoWriter::check_path(std::filesystem::temp_directory_path() / "x" / ".." / ".mp4"),
      RenderError);
  try {
    VideoWriter::check_path(temp_path("clip.webm"));
    FAIL() << "webm accepted";
  } catch (const RenderError& error) {
    EXPECT_NE(std::string(error.what()).find(".webm"), std::string::npos) << error.what();
  }
  EXPECT_EQ(VideoWriter::check_path(temp_path("CLIP.MP4")), VideoFormat::kMp4);
}

TEST(VideoWriter, WrongFrameSizeAndOddMp4SizeAreRefused) {
  const auto path = temp_path("odd.mp4");
  EXPECT_THROW(VideoWriter(path, 63, 48, 30), RenderError);
  VideoWriter writer(path, 64, 48, 30);
  std::vector<std::uint8_t> small(10);
  EXPECT_THROW(writer.write(small), RenderError);
  write_frames(writer, 1);
  writer.close();
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace upkie_rl
