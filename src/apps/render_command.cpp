/// @file
/// `upkie-rl render`: a video of episodes recorded by `upkie-rl rollout --record`; with
/// several record files, their episodes side by side in one video (two policies compared).

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "apps/commands.hpp"
#include "cli/frame_clock.hpp"
#include "cli/video_recorder.hpp"
#include "envs/records/record_file.hpp"
#include "sim/base_observer.hpp"

namespace upkie_rl::apps {
namespace {

struct RenderOptions {
  std::vector<std::string> record_paths;
  VideoOptions video;
};

/// The one walk through a record's episodes: `on_episode(episode)` as each starts, then
/// `on_step(step, episode_return)` for each of its steps, with the return before the step
/// (a row holds the state at t and the reward of the step taken from it).
template <typename OnEpisode, typename OnStep>
void walk_episodes(const std::vector<RecordedStep>& steps, OnEpisode&& on_episode,
                   OnStep&& on_step) {
  int episode = -1;
  double episode_return = 0.0;
  for (const RecordedStep& step : steps) {
    if (step.episode != episode) {
      episode = step.episode;
      episode_return = 0.0;
      on_episode(episode);
    }
    on_step(step, episode_return);
    episode_return += step.reward;
  }
}

void render_one(const std::string& record_path, const VideoOptions& options) {
  const std::vector<RecordedStep> steps = read_record_file(record_path).steps;
  VideoRecorder video(RobotModel::default_model(), options);
  walk_episodes(
      steps, [&video](int episode) { video.start_episode(episode); },
      [&video](const RecordedStep& step, double episode_return) {
        video.add(step.pose, step.time, episode_return, base_pitch(step.pose.base_orientation),
                  step.command ? &*step.command : nullptr,
                  step.measured ? &*step.measured : nullptr);
      });
  video.close();
  std::cout << "video " << options.path.string() << ": " << video.frames() << " frames at "
            << options.fps << " frames/s from " << steps.size() << " steps" << std::endl;
}

/// One frame of a pane: the pose and its caption.
struct PaneFrame {
  RobotPose pose;
  FrameCaption caption;
};

/// The frames of one record file at `fps`, captioned with `label` when `overlay`.
std::vector<PaneFrame> pane_frames(const std::vector<RecordedStep>& steps, const std::string& label,
                                   int fps, bool overlay) {
  std::vector<PaneFrame> frames;
  FrameClock clock(fps);
  int episode = -1;
  walk_episodes(
      steps,
      [&](int started) {
        episode = started;
        clock.start_episode();
      },
      [&](const RecordedStep& step, double episode_return) {
        if (!clock.take(step.time)) return;
        FrameCaption caption;
        if (overlay) {
          caption = episode_caption(episode, step.time, episode_return,
                                    base_pitch(step.pose.base_orientation));
          caption.titles = "record\n" + caption.titles;
          caption.values = label + "\n" + caption.values;
          if (step.command && step.measured) {
            append_velocity_caption(caption, *step.command, *step.measured);
          }
        }
        frames.push_back({step.pose, std::move(caption)});
      });
  return frames;
}

/// The record files' episodes side by side, each pane width / n pixels wide; a record that
/// ends first holds its last frame.
void render_side_by_side(const std::vector<std::string>& record_paths,
                         const VideoOptions& options) {
  constexpr int kMaxPanes = 4;  // one OpenGL context each
  const int panes = static_cast<int>(record_paths.size());
  if (panes > kMaxPanes) {
    throw std::invalid_argument("at most " + std::to_string(kMaxPanes) +
                                " record files side by side, got " + std::to_string(panes));
  }
  VideoOptions pane = options;
  pane.width = options.width / panes / 2 * 2;  // even, for H.264
  std::vector<std::vector<PaneFrame>> frames;
  std::vector<std::unique_ptr<RobotRenderer>> renderers;
  std::size_t length = 0;
  for (const std::string& path : record_paths) {
    frames.push_back(pane_frames(read_record_file(path).steps,
                                 std::filesystem::path(path).stem().string(), options.fps,
                                 options.overlay));
    length = std::max(length, frames.back().size());
    renderers.push_back(
        std::make_unique<RobotRenderer>(RobotModel::default_model(), render_config(pane)));
  }
  const int width = pane.width * panes;
  VideoWriter writer(options.path, width, options.height, options.fps);
  std::vector<std::uint8_t> image(static_cast<std::size_t>(width) * options.height * 3);
  const std::size_t pane_row = static_cast<std::size_t>(pane.width) * 3;
  for (std::size_t f = 0; f < length; ++f) {
    for (int p = 0; p < panes; ++p) {
      const PaneFrame& frame = frames[p][std::min(f, frames[p].size() - 1)];
      const std::span<const std::uint8_t> drawn =
          renderers[p]->render(frame.pose, frame.caption.titles, frame.caption.values);
      for (int y = 0; y < options.height; ++y) {
        std::memcpy(image.data() + (static_cast<std::size_t>(y) * width + p * pane.width) * 3,
                    drawn.data() + y * pane_row, pane_row);
      }
    }
    writer.write(image);
  }
  writer.close();
  std::cout << "video " << options.path.string() << ": " << writer.frames() << " frames at "
            << options.fps << " frames/s, " << panes << " records side by side (" << pane.width
            << "x" << options.height << " each)" << std::endl;
}

void run_render(const RenderOptions& options) {
  VideoWriter::check_path(options.video.path);
  if (options.record_paths.size() == 1) {
    render_one(options.record_paths.front(), options.video);
  } else {
    render_side_by_side(options.record_paths, options.video);
  }
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* command = app.add_subcommand(
      "render",
      "Make a video of episodes recorded by `upkie-rl rollout --record`; several record files "
      "(two policies) play side by side, each in width / n pixels");
  command->add_option("records", options->record_paths, "Record files (CSV)")
      ->required()
      ->check(CLI::ExistingFile);
  add_video_options(*command, options->video);
  command->get_option("--video")->required();  // marked REQUIRED in --help
  command->callback([options] { run_render(*options); });
}

}  // namespace upkie_rl::apps
