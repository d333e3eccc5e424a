// Python binding of one environment (the registry's Env): flat float32 numpy arrays in and
// out, the GIL released while the environment steps.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <mutex>
#include <optional>
#include <span>

#include "array_checks.hpp"
#include "bindings.hpp"
#include "envs/registry/env_factory.hpp"
#include "frame_renderer.hpp"
#include "observation_to_python.hpp"

namespace py = pybind11;

namespace upkie_rl::python {
namespace {

/// One environment. Calls from several Python threads are serialised by a mutex (an Env
/// is not thread-safe); different objects step in parallel.
class PyEnv {
 public:
  PyEnv(const std::string& id, const EnvOptions& options) : env_(make_env(id, options)) {}

  py::array_t<float> reset(std::optional<std::uint64_t> seed) {
    py::array_t<float> observation = new_array<float>({as_size(observation_size())}, "observation");
    std::span<float> out(observation.mutable_data(), observation_size());
    {
      py::gil_scoped_release release;
      const std::lock_guard lock(mutex_);
      env_->reset(seed, out);
    }
    return observation;
  }

  py::tuple step(const FloatArray& action) {
    check_shape(action, 0, env_->action_space().size(), "action");
    py::array_t<float> observation = new_array<float>({as_size(observation_size())}, "observation");
    std::span<float> out(observation.mutable_data(), observation_size());
    std::span<const float> in(action.data(), env_->action_space().size());
    StepResult result;
    {
      py::gil_scoped_release release;
      const std::lock_guard lock(mutex_);
      result = env_->step(in, out);
    }
    return py::make_tuple(std::move(observation), result.reward, result.terminated,
                          result.truncated);
  }

  void set_randomization_scale(double scale) {
    const std::lock_guard lock(mutex_);
    env_->set_randomization_scale(scale);
  }

  py::object spine_observation() const {
    const std::lock_guard lock(mutex_);
    const Observation* full = env_->full_observation();
    if (full == nullptr) return py::none();
    return observation_to_python(*full);
  }

  py::array_t<float> neutral_action() const {
    py::array_t<float> action =
        new_array<float>({as_size(env_->action_space().size())}, "neutral action");
    env_->neutral_action(std::span<float>(action.mutable_data(), env_->action_space().size()));
    return action;
  }

  /// The robot drawn from the last state's ground truth, (height, width, 3) uint8, with the
  /// time and pitch written on it when `overlay` is true.
  py::array_t<std::uint8_t> render(int width, int height, bool overlay) {
    const std::lock_guard lock(mutex_);
    return renderer_.render(env_->full_observation(), width, height, overlay);
  }

  const Env& env() const { return *env_; }

 private:
  std::size_t observation_size() const { return env_->observation_space().size(); }

  std::unique_ptr<Env> env_;
  FrameRenderer renderer_;
  mutable std::mutex mutex_;
};

}  // namespace

py::tuple space_to_python(const BoxSpace& space) {
  py::array_t<float> low = new_array<float>({as_size(space.size())}, "space low");
  py::array_t<float> high = new_array<float>({as_size(space.size())}, "space high");
  std::copy(space.low.begin(), space.low.end(), low.mutable_data());
  std::copy(space.high.begin(), space.high.end(), high.mutable_data());
  return py::make_tuple(std::move(low), std::move(high), space.names);
}

void bind_env(py::module_& module) {
  py::class_<PyEnv>(module, "Env", "One upkie-rl environment on flat float32 arrays.")
      .def(py::init<const std::string&, const EnvOptions&>(), py::arg("env_id"),
           py::arg("options") = EnvOptions{})
      .def("reset", &PyEnv::reset, py::arg("seed") = py::none(),
           "Starts an episode; returns the first observation.")
      .def("step", &PyEnv::step, py::arg("action").noconvert(),
           "Steps with a float32 action; returns (observation, reward, terminated, "
           "truncated).")
      .def("spine_observation", &PyEnv::spine_observation,
           "The full observation dictionary of the last reset or step (upkie's "
           "info['spine_observation']), or None.")
      .def("neutral_action", &PyEnv::neutral_action)
      .def("set_randomization_scale", &PyEnv::set_randomization_scale, py::arg("scale"),
           "Multiplies every randomisation bound (initial state, perturbations, noise, lag, "
           "pushes) by scale in [0, 1] from the next reset on (a curriculum).")
      .def("render", &PyEnv::render, py::arg("width") = 640, py::arg("height") = 480,
           py::arg("overlay") = false,
           "The robot drawn offscreen from the last state's ground truth: a (height, width, "
           "3) uint8 array; overlay=True writes the time and pitch on it.")
      .def_property_readonly(
          "observation_space",
          [](const PyEnv& self) { return space_to_python(self.env().observation_space()); })
      .def_property_readonly(
          "action_space",
          [](const PyEnv& self) { return space_to_python(self.env().action_space()); })
      .def_property_readonly("timestep", [](const PyEnv& self) { return self.env().timestep(); })
      .def_property_readonly("physics_steps_per_step",
                             [](const PyEnv& self) { return self.env().physics_steps_per_step(); });
}

}  // namespace upkie_rl::python
