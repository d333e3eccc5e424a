// Python binding of a vector environment: one call steps every environment in C++ with the
// GIL released (a thread pool when num_threads > 0); results come back as numpy arrays.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>

#include "array_checks.hpp"
#include "bindings.hpp"
#include "frame_renderer.hpp"
#include "observation_to_python.hpp"
#include "vec/make_vector_env.hpp"

namespace py = pybind11;

namespace upkie_rl::python {
namespace {

AutoresetMode parse_autoreset_mode(const std::string& mode) {
  if (mode == "same_step") return AutoresetMode::kSameStep;
  if (mode == "next_step") return AutoresetMode::kNextStep;
  throw std::invalid_argument("autoreset mode \"" + mode + "\": expected same_step or next_step");
}

/// A copy of `values` as a numpy array of `shape`.
template <typename T, typename Source>
py::array_t<T> to_numpy(const Source* values, std::vector<py::ssize_t> shape) {
  py::array_t<T> array = new_array<T>(std::move(shape), "array");
  std::copy(values, values + array.size(), array.mutable_data());
  return array;
}

/// n environments of one id. Calls from several Python threads are serialised.
class PyVectorEnv {
 public:
  PyVectorEnv(const std::string& id, const EnvOptions& options, std::size_t num_envs,
              std::size_t num_threads, const std::string& autoreset_mode)
      : venv_(make_vector_env(id, options, num_envs, num_threads,
                              parse_autoreset_mode(autoreset_mode))),
        num_threads_(num_threads == 0 ? 0 : std::min(num_threads, num_envs)) {}

  py::array_t<float> reset(std::optional<std::uint64_t> seed) {
    std::span<const float> observations;
    {
      py::gil_scoped_release release;
      const std::lock_guard lock(mutex_);
      observations = venv_->reset(seed);
    }
    was_reset_ = true;
    return to_numpy<float>(observations.data(), {rows(), observation_size()});
  }

  py::tuple step(const FloatArray& actions) {
    check_shape(actions, venv_->num_envs(), venv_->action_space().size(), "actions");
    if (!was_reset_) throw std::logic_error("vector env: step() called before reset()");
    const std::span<const float> in(actions.data(), static_cast<std::size_t>(actions.size()));
    const VectorStep* result = nullptr;
    {
      py::gil_scoped_release release;
      const std::lock_guard lock(mutex_);
      result = &venv_->step(in);
      last_step_ = result;
    }
    return py::make_tuple(
        to_numpy<float>(result->observations.data(), {rows(), observation_size()}),
        to_numpy<float>(result->rewards.data(), {rows()}),
        to_numpy<bool>(result->terminated.data(), {rows()}),
        to_numpy<bool>(result->truncated.data(), {rows()}));
  }

  /// Last observations of the episodes that ended at the last step (rows of the others are
  /// stale), their raw returns and lengths.
  py::tuple final_observations() {
    const std::lock_guard lock(mutex_);
    if (last_step_ == nullptr) throw std::logic_error("vector env: no step yet");
    const VectorStep& last = *last_step_;
    return py::make_tuple(
        to_numpy<float>(last.final_observations.data(), {rows(), observation_size()}),
        to_numpy<double>(last.episode_returns.data(), {rows()}),
        to_numpy<std::int64_t>(last.episode_lengths.data(), {rows()}));
  }

  py::object spine_observation(std::size_t i) const {
    if (i >= venv_->num_envs()) throw py::index_error("no environment " + std::to_string(i));
    const std::lock_guard lock(mutex_);
    const Observation* full = venv_->full_observation(i);
    if (full == nullptr) return py::none();
    return observation_to_python(*full);
  }

  /// Environment `i` drawn from its last state's ground truth, (height, width, 3) uint8.
  py::array_t<std::uint8_t> render(std::size_t i, int width, int height, bool overlay) {
    if (i >= venv_->num_envs()) throw py::index_error("no environment " + std::to_string(i));
    const std::lock_guard lock(mutex_);
    return renderer_.render(venv_->full_observation(i), width, height, overlay);
  }

  const VectorEnv& venv() const { return *venv_; }
  std::size_t num_threads() const { return num_threads_; }

 private:
  py::ssize_t rows() const { return static_cast<py::ssize_t>(venv_->num_envs()); }
  py::ssize_t observation_size() const {
    return static_cast<py::ssize_t>(venv_->observation_space().size());
  }

  std::unique_ptr<VectorEnv> venv_;
  std::size_t num_threads_;
  bool was_reset_ = false;
  const VectorStep* last_step_ = nullptr;  // The VectorEnv's buffers of the last step().
  FrameRenderer renderer_;                 // One OpenGL context for every environment's frames.
  mutable std::mutex mutex_;
};

}  // namespace

void bind_vector_env(py::module_& module) {
  py::class_<PyVectorEnv>(module, "VectorEnv", "n upkie-rl environments stepped together in C++.")
      .def(py::init<const std::string&, const EnvOptions&, std::size_t, std::size_t,
                    const std::string&>(),
           py::arg("env_id"), py::arg("options"), py::arg("num_envs"), py::arg("num_threads"),
           py::arg("autoreset_mode") = "same_step")
      .def("reset", &PyVectorEnv::reset, py::arg("seed") = py::none(),
           "Resets every environment, env i with seed + i; returns the observations.")
      .def("step", &PyVectorEnv::step, py::arg("actions").noconvert(),
           "Steps every environment with its row of float32 actions; returns (observations, "
           "rewards, terminated, truncated).")
      .def("final_observations", &PyVectorEnv::final_observations,
           "(final observations, episode returns, episode lengths) of the last step.")
      .def("spine_observation", &PyVectorEnv::spine_observation, py::arg("index"))
      .def("render", &PyVectorEnv::render, py::arg("index"), py::arg("width") = 640,
           py::arg("height") = 480, py::arg("overlay") = false,
           "Environment index drawn offscreen from its last state's ground truth: a (height, "
           "width, 3) uint8 array; overlay=True writes the time and pitch on it.")
      .def_property_readonly("num_envs",
                             [](const PyVectorEnv& self) { return self.venv().num_envs(); })
      .def_property_readonly("num_threads", &PyVectorEnv::num_threads)
      .def_property_readonly(
          "observation_space",
          [](const PyVectorEnv& self) { return space_to_python(self.venv().observation_space()); })
      .def_property_readonly("action_space", [](const PyVectorEnv& self) {
        return space_to_python(self.venv().action_space());
      });
}

}  // namespace upkie_rl::python
