#include "cli/video_recorder.hpp"

#include "cli/option_checks.hpp"

#include <cmath>
#include <cstdio>

namespace upkie_rl::apps {

RenderConfig render_config(const VideoOptions& options) {
  RenderConfig config;
  config.width = options.width;
  config.height = options.height;
  config.bumps = options.bumps;
  return config;
}

VideoRecorder::VideoRecorder(std::shared_ptr<const RobotModel> model, const VideoOptions& options)
    : options_(options),
      renderer_((VideoWriter::check_path(options.path), std::move(model)), render_config(options)),
      writer_(options.path, options.width, options.height, options.fps),
      clock_(options.fps) {}

FrameCaption episode_caption(int episode, double time, double episode_return, double pitch) {
  char values[160];
  std::snprintf(values, sizeof(values), "%d\n%.2f s\n%.1f\n%+.3f rad", episode, time,
                episode_return, pitch);
  return {"episode\ntime\nreturn\npitch", values};
}

void append_velocity_caption(FrameCaption& caption, const VelocityCommand& command,
                             const BaseVelocity& measured) {
  char values[96];
  std::snprintf(values, sizeof(values), "\n%+.2f m/s %+.2f rad/s\n%+.2f m/s %+.2f rad/s",
                command.forward_velocity, command.yaw_rate, measured.forward_velocity,
                measured.yaw_rate);
  caption.titles += "\ncommand\nmeasured";
  caption.values += values;
}

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
        if (!parse_frame_size(size, options.width, options.height)) {
          throw CLI::ValidationError("--video-size", "expected WIDTHxHEIGHT, got " + size);
        }
      },
      "Frame size WIDTHxHEIGHT (default 640x480)");
  command.add_flag(
      "--overlay,!--no-overlay", options.overlay,
      "Write the episode, time [s], return and pitch [rad] on the frames (default: on; "
      "the caption scales with the frame)");
}

void VideoRecorder::start_episode(int episode) {
  episode_ = episode;
  clock_.start_episode();
}

void VideoRecorder::add(const RobotPose& pose, double time, double episode_return, double pitch,
                        const VelocityCommand* command, const BaseVelocity* measured) {
  if (!clock_.take(time)) return;
  FrameCaption caption;
  if (options_.overlay) {
    caption = episode_caption(episode_, time, episode_return, pitch);
    if (command != nullptr && measured != nullptr) {
      append_velocity_caption(caption, *command, *measured);
    }
  }
  writer_.write(renderer_.render(pose, caption.titles, caption.values));
}

void VideoRecorder::close() { writer_.close(); }

}  // namespace upkie_rl::apps
