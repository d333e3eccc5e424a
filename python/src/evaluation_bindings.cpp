// Python binding of the evaluations' shared rules (envs/evaluation/evaluation_start.hpp): the
// random initial state episodes start from, and the warning for identical episodes.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "envs/evaluation/evaluation_start.hpp"

namespace py = pybind11;

namespace upkie_rl::python {

void bind_evaluation(py::module_& module) {
  module.def(
      "evaluation_start_options",
      [](const std::string& env_id, const std::vector<std::string>& given) {
        EnvOptions given_options;
        for (const std::string& name : given) given_options.emplace_back(name, "");
        std::vector<std::pair<std::string, double>> added;
        for (const auto& [name, value] : evaluation_start_options(env_id, given_options)) {
          added.emplace_back(name, std::stod(value));
        }
        return added;
      },
      py::arg("env_id"), py::arg("given_names"),
      "(name, bound) of each initial-state randomisation evaluations add to the options "
      "named in given_names.");
  module.def(
      "identical_episodes_warning",
      [](const std::vector<double>& returns, const std::vector<int>& lengths) {
        return identical_episodes_warning(returns, lengths);
      },
      py::arg("returns"), py::arg("lengths"),
      "A warning when every episode had the same return and length, else ''.");
}

}  // namespace upkie_rl::python
