/// @file
/// `upkie-rl render`: a video of episodes recorded by `upkie-rl rollout --record`.

#include <iostream>
#include <memory>
#include <string>

#include "apps/commands.hpp"
#include "apps/record_file.hpp"
#include "apps/video_recorder.hpp"
#include "sim/base_observer.hpp"

namespace upkie_rl::apps {
namespace {

struct RenderOptions {
  std::string record_path;
  VideoOptions video;
};

void run_render(const RenderOptions& options) {
  if (options.video.path.empty()) throw std::invalid_argument("--video is required");
  VideoWriter::check_path(options.video.path);
  const std::vector<RecordedStep> steps = read_record_file(options.record_path).steps;
  VideoRecorder video(RobotModel::default_model(), options.video);
  int episode = -1;
  double episode_return = 0.0;
  for (const RecordedStep& step : steps) {
    if (step.episode != episode) {
      episode = step.episode;
      episode_return = 0.0;
      video.start_episode(episode);
    }
    // A row holds the state at t and the reward of the step taken from it.
    video.add(step.pose, step.time, episode_return, base_pitch(step.pose.base_orientation));
    episode_return += step.reward;
  }
  video.close();
  std::cout << "video " << options.video.path.string() << ": " << video.frames() << " frames at "
            << options.video.fps << " frames/s from " << steps.size() << " steps" << std::endl;
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* command = app.add_subcommand(
      "render", "Make a video of episodes recorded by `upkie-rl rollout --record`");
  command->add_option("record", options->record_path, "Record file (CSV)")
      ->required()
      ->check(CLI::ExistingFile);
  add_video_options(*command, options->video);
  command->callback([options] { run_render(*options); });
}

}  // namespace upkie_rl::apps
