// Python binding of DeployedPolicy: a trained model of `upkie-rl train` evaluated without
// libtorch (the GIL released while it runs).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <mutex>

#include "array_checks.hpp"
#include "bindings.hpp"
#include "policy/deployed_policy.hpp"

namespace py = pybind11;

namespace upkie_rl::python {
namespace {

/// One loaded policy; calls from several threads are serialised (it reuses its buffers).
class PyPolicy {
 public:
  explicit PyPolicy(const std::string& path) : policy_(DeployedPolicy::load(path)) {}

  py::array_t<float> act(const FloatArray& observation) {
    check_shape(observation, 0, policy_.observation_space().size(), "observation");
    py::array_t<float> action =
        new_array<float>({as_size(policy_.action_space().size())}, "action");
    run(observation, action, false);
    return action;
  }

  py::array_t<float> act_batch(const FloatArray& observations) {
    const auto rows =
        static_cast<std::size_t>(observations.ndim() == 2 ? observations.shape(0) : 0);
    check_shape(observations, rows, policy_.observation_space().size(), "observations");
    py::array_t<float> actions =
        new_array<float>({as_size(rows), as_size(policy_.action_space().size())}, "actions");
    run(observations, actions, true);
    return actions;
  }

  const DeployedPolicy& policy() const { return policy_; }

 private:
  void run(const FloatArray& in, py::array_t<float>& out, bool batch) {
    std::span<const float> observations(in.data(), static_cast<std::size_t>(in.size()));
    std::span<float> actions(out.mutable_data(), static_cast<std::size_t>(out.size()));
    py::gil_scoped_release release;
    const std::lock_guard lock(mutex_);
    if (batch) {
      policy_.act_batch(observations, actions);
    } else {
      policy_.act(observations, actions);
    }
  }

  DeployedPolicy policy_;
  std::mutex mutex_;
};

}  // namespace

void bind_policy(py::module_& module) {
  py::class_<PyPolicy>(module, "Policy", "A trained policy read from a model or checkpoint.")
      .def(py::init<const std::string&>(), py::arg("path"))
      .def("act", &PyPolicy::act, py::arg("observation").noconvert())
      .def("act_batch", &PyPolicy::act_batch, py::arg("observations").noconvert())
      .def_property_readonly("env_id", [](const PyPolicy& self) { return self.policy().env_id(); })
      .def_property_readonly(
          "observation_space",
          [](const PyPolicy& self) { return space_to_python(self.policy().observation_space()); })
      .def_property_readonly("action_space", [](const PyPolicy& self) {
        return space_to_python(self.policy().action_space());
      });
}

}  // namespace upkie_rl::python
