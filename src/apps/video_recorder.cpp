#include "apps/video_recorder.hpp"

#include "apps/option_checks.hpp"

#include <cmath>
#include <cstdio>

namespace upkie_rl::apps {
namespace {

RenderConfig render_config(const VideoOptions& options) {
  RenderConfig config;
  config.width = options.width;
  config.height = options.height;
  return config;
}

}  // namespace

VideoRecorder::VideoRecorder(std::shared_ptr<const RobotModel> model, const VideoOptions& options)
    : options_(options),
      renderer_((VideoWriter::check_path(options.path), std::move(model)), render_config(options)),
      writer_(options.path, options.width, options.height, options.fps) {}

void add_video_options(CLI::App& command, VideoOptions& options) {
  command
      .add_option("--video", options.path,
                  "Write a video of the episodes: out.mp4 (H.264) or out.gif, real time")
      ->check(kNonEmptyPath);
  command.add_option("--video-fps", options.fps, "Video frames per second")
      ->check(CLI::IsMember({30, 60}))
      ->capture_default_str();
  command.add_option_function<std::string>(
      "--video-size",
      [&options](const std::string& size) {
        const std::size_t x = size.find('x');
        try {
          if (x == std::string::npos) throw std::invalid_argument(size);
          options.width = std::stoi(size.substr(0, x));
          options.height = std::stoi(size.substr(x + 1));
        } catch (const std::exception&) {
          throw CLI::ValidationError("--video-size", "expected WIDTHxHEIGHT, got " + size);
        }
      },
      "Frame size WIDTHxHEIGHT (default 640x480)");
}

void VideoRecorder::start_episode(int episode) {
  episode_ = episode;
  next_frame_ = 0;
}

void VideoRecorder::add(const RobotPose& pose, double time, double episode_return, double pitch,
                        const VelocityCommand* command, const BaseVelocity* measured) {
  // Half a step of tolerance: at 200 Hz and 30 fps, frame k is the first step at or after
  // k / 30 s.
  if (time + 1e-9 < static_cast<double>(next_frame_) / options_.fps) return;
  char values[320];
  const int length = std::snprintf(values, sizeof(values), "%d\n%.2f s\n%.1f\n%+.3f rad", episode_,
                                   time, episode_return, pitch);
  const bool velocity = command != nullptr && measured != nullptr;
  if (velocity && length > 0 && static_cast<std::size_t>(length) < sizeof(values)) {
    std::snprintf(values + length, sizeof(values) - static_cast<std::size_t>(length),
                  "\n%+.2f m/s %+.2f rad/s\n%+.2f m/s %+.2f rad/s", command->forward_velocity,
                  command->yaw_rate, measured->forward_velocity, measured->yaw_rate);
  }
  const std::span<const std::uint8_t> frame = renderer_.render(
      pose,
      velocity ? "episode\ntime\nreturn\npitch\ncommand\nmeasured" : "episode\ntime\nreturn\npitch",
      values);
  writer_.write(frame);
  next_frame_ = static_cast<long>(std::floor(time * options_.fps + 1e-9)) + 1;
}

void VideoRecorder::close() { writer_.close(); }

}  // namespace upkie_rl::apps
