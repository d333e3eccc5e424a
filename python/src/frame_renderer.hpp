#pragma once
/// @file
/// FrameRenderer: the robot of an environment's last state as a numpy image, for the
/// Python `render()` of single and vector environments.

#include <pybind11/numpy.h>

#include <cstdint>
#include <memory>

#include "render/robot_renderer.hpp"
#include "sim/observation.hpp"

namespace upkie_rl::python {

/// Owns one offscreen renderer (an OpenGL context), made at the first frame on the calling
/// thread and made again when the size changes.
class FrameRenderer {
 public:
  /// The robot drawn from `observation`'s ground truth, a (height, width, 3) uint8 array;
  /// with `overlay`, the time and pitch in the top left corner.
  /// @throws RenderError when `observation` is null or has no ground truth (a Spine env's).
  pybind11::array_t<std::uint8_t> render(const Observation* observation, int width, int height,
                                         bool overlay);

 private:
  std::unique_ptr<RobotRenderer> renderer_;
};

}  // namespace upkie_rl::python
