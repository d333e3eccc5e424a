/// Frames per second of the offscreen renderer (Mesa EGL, software) and of the H.264 encoder
/// that `rollout --video` feeds, at the default 640x480.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>

#include "render/robot_renderer.hpp"
#include "render/video_writer.hpp"

namespace upkie_rl {
namespace {

/// A pose that changes at each frame, as in a rollout.
RobotPose moving_pose(long frame) {
  RobotPose pose;
  pose.base_position = Eigen::Vector3d(0.01 * frame, 0.0, 0.56);
  pose.base_orientation = Eigen::AngleAxisd(0.2 * std::sin(0.1 * frame), Eigen::Vector3d::UnitY());
  return pose;
}

void BM_RenderFrame(benchmark::State& state) {
  RenderConfig config;
  config.width = static_cast<int>(state.range(0));
  config.height = static_cast<int>(state.range(1));
  RobotRenderer renderer(RobotModel::default_model(), config);
  long frame = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(renderer.render(moving_pose(frame++), "time", "1.00 s").data());
  }
  state.counters["frames_per_s"] =
      benchmark::Counter(static_cast<double>(frame), benchmark::Counter::kIsRate);
}

void BM_RenderAndEncodeMp4(benchmark::State& state) {
  RobotRenderer renderer(RobotModel::default_model(), RenderConfig{});
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "upkie_rl_render_bench.mp4";
  VideoWriter writer(path, 640, 480, 30);
  long frame = 0;
  for (auto _ : state) writer.write(renderer.render(moving_pose(frame++), "time", "1.00 s"));
  writer.close();
  std::filesystem::remove(path);
  state.counters["frames_per_s"] =
      benchmark::Counter(static_cast<double>(frame), benchmark::Counter::kIsRate);
}

BENCHMARK(BM_RenderFrame)
    ->Args({640, 480})
    ->Args({320, 240})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_RenderAndEncodeMp4)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace upkie_rl
