#include "frame_renderer.hpp"

#include <algorithm>
#include <cstdio>

#include "array_checks.hpp"
#include "render/render_error.hpp"

namespace py = pybind11;

namespace upkie_rl::python {

py::array_t<std::uint8_t> FrameRenderer::render(const Observation* observation, int width,
                                                int height, bool overlay) {
  if (observation == nullptr || !observation->has_sim) {
    throw RenderError("this environment has no simulator ground truth to render");
  }
  if (!renderer_ || renderer_->width() != width || renderer_->height() != height) {
    RenderConfig config;
    config.width = width;
    config.height = height;
    renderer_.reset();
    renderer_ = std::make_unique<RobotRenderer>(RobotModel::default_model(), config);
  }
  char values[96] = "";
  if (overlay) {
    std::snprintf(values, sizeof(values), "%.2f s\n%+.3f rad", observation->time,
                  observation->base_orientation.pitch);
  }
  const std::span<const std::uint8_t> frame =
      renderer_->render(robot_pose(*observation), overlay ? "time\npitch" : "", values);
  py::array_t<std::uint8_t> image = new_array<std::uint8_t>({height, width, 3}, "frame");
  std::copy(frame.begin(), frame.end(), image.mutable_data());
  return image;
}

}  // namespace upkie_rl::python
