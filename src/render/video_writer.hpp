#pragma once
/// @file
/// VideoWriter: frames to an H.264 MP4 (browser-playable) or a GIF, through FFmpeg.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

namespace upkie_rl {

/// Video container chosen by the file extension.
enum class VideoFormat { kMp4, kGif };

/// Streams RGB frames to an `ffmpeg` process (Debian's `ffmpeg` package) that encodes them:
/// MP4 as H.264 in yuv420p with the index first (plays in browsers while loading), GIF with
/// a palette computed from the whole clip.
class VideoWriter {
 public:
  /// Checks, before anything runs, that `path` can become a video: a .mp4 or .gif
  /// extension, an existing writable directory, and an `ffmpeg` on the PATH.
  /// @throws RenderError naming the problem.
  static VideoFormat check_path(const std::filesystem::path& path);

  /// Starts the encoder for frames of width x height pixels at `fps` frames per second.
  /// @throws RenderError on a bad path (see check_path), an odd size for MP4, or when
  ///         ffmpeg cannot start.
  VideoWriter(const std::filesystem::path& path, int width, int height, int fps);
  /// Finishes the file if close() was not called (errors are then only logged).
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  /// Appends a frame of height rows of width RGB pixels, top row first.
  /// @throws RenderError on a frame of the wrong size or when ffmpeg stopped.
  void write(std::span<const std::uint8_t> rgb);

  /// Ends the stream and waits for ffmpeg.
  /// @throws RenderError with ffmpeg's exit status when it failed.
  void close();

  int frames() const { return frames_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  int width_;
  int height_;
  int fps_;
  int frames_ = 0;
  int stdin_fd_ = -1;
  int pid_ = -1;
};

}  // namespace upkie_rl
