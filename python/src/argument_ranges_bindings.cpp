// The ranges of the integer arguments the Python package passes to the bindings, from their
// C++ declarations, so that the package checks them (upkie_rl/arguments.py) against the
// same numbers as the command line and the C++ layers, and pybind11 never sees an integer
// it cannot convert.

#include <pybind11/pybind11.h>

#include <cstdint>
#include <limits>

#include "bindings.hpp"
#include "envs/evaluation/evaluation_start.hpp"
#include "render/robot_renderer.hpp"
#include "vec/make_vector_env.hpp"

namespace py = pybind11;

namespace upkie_rl::python {

void bind_argument_ranges(py::module_& module) {
  py::dict ranges;
  ranges["num_envs"] = py::make_tuple(1, kMaxVectorEnvs);
  ranges["num_threads"] = py::make_tuple(0, kMaxEnvThreads);
  ranges["render_envs"] = py::make_tuple(1, kMaxVectorEnvs);
  ranges["render_width"] = py::make_tuple(kMinFrameWidth, kMaxFrameWidth);
  ranges["render_height"] = py::make_tuple(kMinFrameHeight, kMaxFrameHeight);
  ranges["seed"] = py::make_tuple(0, std::numeric_limits<std::uint64_t>::max());
  ranges["episodes"] = py::make_tuple(1, kMaxEvaluationEpisodes);
  module.attr("ARGUMENT_RANGES") = ranges;
}

}  // namespace upkie_rl::python
