/// `upkie-rl rollout --video` and `upkie-rl render`: videos from the real binary, checked
/// with ffprobe.

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "apps/cli_runner.hpp"
#include "common/shell_output.hpp"
#include "common/temp_files.hpp"

namespace upkie_rl {
namespace {

using testing::run_cli;
using testing::shell_output;
using testing::temp_path;

/// "frames duration" of a video's first stream.
std::pair<int, double> probe(const std::filesystem::path& path) {
  const std::string frames = shell_output(
      "ffprobe -v error -select_streams v:0 -count_frames "
      "-show_entries stream=nb_read_frames -of csv=p=0 " +
      path.string());
  const std::string duration =
      shell_output("ffprobe -v error -show_entries format=duration -of csv=p=0 " + path.string());
  return {frames.empty() ? -1 : std::stoi(frames), duration.empty() ? -1.0 : std::stod(duration)};
}

TEST(VideoCommand, RolloutVideoPlaysInRealTime) {
  // 120 steps at 200 Hz: 0.6 s of simulated time, 0.6 * 30 = 18 frames (t = 0 included).
  const auto path = temp_path("rollout.mp4");
  const auto result = run_cli(
      "rollout --env Upkie-MuJoCo-Pendulum --controller linear:10,1,0,0.1 --max-steps 120 "
      "--video-size 320x240 --video " +
      path.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("19 frames at 30 frames/s"), std::string::npos) << result.output;
  const auto [frames, duration] = probe(path);
  EXPECT_EQ(frames, 19);
  EXPECT_NEAR(duration, 19.0 / 30.0, 0.01);
  std::filesystem::remove(path);
}

/// White pixels (the caption's text) in the top left quarter of a video's first frame.
long caption_pixels(const std::filesystem::path& video) {
  const std::string raw = shell_output("ffmpeg -v error -i '" + video.string() +
                                       "' -frames:v 1 -vf crop=iw/2:ih/2:0:0 -f rawvideo "
                                       "-pix_fmt rgb24 - 2>/dev/null");
  long count = 0;
  for (std::size_t i = 0; i + 2 < raw.size(); i += 3) {
    const auto bright = [&](std::size_t c) { return static_cast<unsigned char>(raw[i + c]) > 225; };
    count += bright(0) && bright(1) && bright(2) ? 1 : 0;
  }
  return count;
}

TEST(VideoCommand, OverlayIsOptional) {
  const auto captioned = temp_path("captioned.mp4");
  const auto clean = temp_path("clean.mp4");
  const std::string rollout =
      "rollout --env Upkie-MuJoCo-Pendulum --max-steps 10 --video-size 320x240 --video ";
  ASSERT_EQ(run_cli(rollout + captioned.string()).exit_code, 0);
  const auto result = run_cli(rollout + clean.string() + " --no-overlay");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_GT(caption_pixels(captioned), 20);  // small white text, blurred by H.264
  EXPECT_EQ(caption_pixels(clean), 0);
  std::filesystem::remove(captioned);
  std::filesystem::remove(clean);
}

TEST(VideoCommand, RenderPutsTwoRecordsSideBySide) {
  const auto falling = temp_path("falling.csv");
  const auto balancing = temp_path("balancing.csv");
  const auto video = temp_path("side_by_side.mp4");
  const std::string rollout = "rollout --env Upkie-MuJoCo-Pendulum --exact-start --record ";
  ASSERT_EQ(run_cli(rollout + falling.string() + " --max-steps 60").exit_code, 0);
  ASSERT_EQ(
      run_cli(rollout + balancing.string() + " --max-steps 120 --controller linear:10,1,0,0.1")
          .exit_code,
      0);
  const auto result = run_cli("render " + falling.string() + " " + balancing.string() +
                              " --video-size 640x240 --video " + video.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("2 records side by side (320x240 each)"), std::string::npos)
      << result.output;
  // The longer record sets the length: its rows hold the states before each step (0 to
  // 0.595 s), 18 frames at 30 frames/s; the shorter one holds its last frame.
  EXPECT_EQ(probe(video).first, 18);
  EXPECT_EQ(shell_output("ffprobe -v error -select_streams v:0 -show_entries stream=width,height "
                         "-of csv=p=0 " +
                         video.string()),
            "640,240\n");
  for (const auto& path : {falling, balancing, video}) std::filesystem::remove(path);
}

TEST(VideoCommand, BulletEpisodesRenderToo) {
  const auto path = temp_path("bullet.gif");
  const auto result = run_cli(
      "rollout --env Upkie-Bullet-Pendulum --max-steps 40 --video-fps 60 "
      "--video-size 160x120 --video " +
      path.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(probe(path).first, 13);  // 0.2 s at 60 frames/s, t = 0 included
  std::filesystem::remove(path);
}

TEST(VideoCommand, BadVideoPathsFailBeforeTheRollout) {
  for (const std::string& bad :
       {temp_path("out.avi").string(), std::string("/nonexistent_upkie_dir/out.mp4")}) {
    const auto result = run_cli("rollout --env Upkie-MuJoCo-Pendulum --max-steps 5 --video " + bad);
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find("video " + bad), std::string::npos) << result.output;
    EXPECT_EQ(result.output.find("episode 0"), std::string::npos) << "the rollout ran";
  }
}

TEST(VideoCommand, RenderMakesAVideoOfARecordedRollout) {
  const auto record = temp_path("episodes.csv");
  const auto video = temp_path("replay.mp4");
  const auto rollout = run_cli(
      "rollout --env Upkie-Bullet-Pendulum --controller linear:10,1,0,0.1 --episodes 2 "
      "--max-steps 60 --record " +
      record.string());
  ASSERT_EQ(rollout.exit_code, 0) << rollout.output;
  const auto result =
      run_cli("render " + record.string() + " --video-size 320x240 --video " + video.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  // Two episodes of 60 rows (t = 0 to 0.295 s): frames at 0, 1/30, ..., 8/30 in each.
  EXPECT_EQ(probe(video).first, 18);
  std::filesystem::remove(video);
  std::filesystem::remove(record);
}

TEST(VideoCommand, RenderRefusesMalformedRecords) {
  const auto video = temp_path("never.mp4");
  const auto write = [](const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path) << text;
  };
  const auto no_columns = temp_path("no_columns.csv");
  write(no_columns, "episode,step,t,reward\n0,0,0,1\n");
  auto result = run_cli("render " + no_columns.string() + " --video " + video.string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("no column \"base_x\""), std::string::npos) << result.output;

  const auto record = temp_path("good.csv");
  ASSERT_EQ(run_cli("rollout --env Upkie-Bullet-Pendulum --max-steps 3 --record " + record.string())
                .exit_code,
            0);
  std::ifstream in(record);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  const auto truncated = temp_path("truncated.csv");
  write(truncated, header + "\n" + row + "\n" + row.substr(0, row.size() / 2) + "\n");
  result = run_cli("render " + truncated.string() + " --video " + video.string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find(":3: "), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("truncated file?"), std::string::npos) << result.output;

  const auto not_number = temp_path("not_number.csv");
  write(not_number, header + "\n" + "zero" + row.substr(row.find(',')) + "\n");
  result = run_cli("render " + not_number.string() + " --video " + video.string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("column episode is not a number"), std::string::npos)
      << result.output;
  EXPECT_FALSE(std::filesystem::exists(video));
  for (const auto& path : {no_columns, record, truncated, not_number}) {
    std::filesystem::remove(path);
  }
}

}  // namespace
}  // namespace upkie_rl
