#pragma once
/// @file
/// VideoRecorder: turns the steps of episodes into a real-time video with a caption.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <memory>

#include "cli/frame_clock.hpp"
#include "envs/tasks/velocity_command.hpp"
#include "render/robot_renderer.hpp"
#include "render/video_writer.hpp"

namespace upkie_rl::apps {

/// The caption of a frame: titles and values, two columns of lines.
struct FrameCaption {
  std::string titles;
  std::string values;
};

/// "episode\ntime\nreturn\npitch" and their values ("3", "1.25 s", "-12.5", "+0.012 rad").
FrameCaption episode_caption(int episode, double time, double episode_return, double pitch);

/// Adds the "command" and "measured" lines of a velocity task ("+0.50 m/s +0.10 rad/s").
void append_velocity_caption(FrameCaption& caption, const VelocityCommand& command,
                             const BaseVelocity& measured);

/// Settings of `--video`.
struct VideoOptions {
  std::filesystem::path path;  ///< .mp4 or .gif.
  int fps = 30;                ///< Frames per second of video = of simulated time.
  int width = 640;
  int height = 480;
  bool overlay = true;  ///< Caption (episode, time, return, pitch) on the frames.
  FloorBumps bumps{};   ///< The simulated world's bumps, drawn on the floor.
};

/// The renderer's settings of a video's frames.
RenderConfig render_config(const VideoOptions& options);

/// Adds --video, --video-fps, --video-size, --overlay/--no-overlay to a subcommand.
void add_video_options(CLI::App& command, VideoOptions& options);

/// Renders the robot at `fps` frames per simulated second: a step becomes a frame when its
/// time reaches the next frame's, so the video plays in real time whatever the agent rate.
/// Each frame shows the episode, time, return so far and pitch (and, for a velocity task,
/// the command beside the measured velocity) unless options.overlay is false.
class VideoRecorder {
 public:
  /// Checks the path and starts the renderer and the encoder.
  /// @throws RenderError naming the problem.
  VideoRecorder(std::shared_ptr<const RobotModel> model, const VideoOptions& options);

  /// Starts episode `episode`: its first frame is at its time 0.
  void start_episode(int episode);

  /// Offers the state at simulated time `time` [s] of the current episode; a velocity
  /// task's frames also show its command and the measured velocity (`command`, `measured`).
  void add(const RobotPose& pose, double time, double episode_return, double pitch,
           const VelocityCommand* command = nullptr, const BaseVelocity* measured = nullptr);

  /// Finishes the file. @throws RenderError when the encoder failed.
  void close();

  int frames() const { return writer_.frames(); }

 private:
  VideoOptions options_;
  RobotRenderer renderer_;
  VideoWriter writer_;
  FrameClock clock_;
  int episode_ = 0;
};

}  // namespace upkie_rl::apps
