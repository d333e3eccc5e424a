// The `upkie_rl._core` extension module: thin bindings of the C++ environment layers
// (envs, vec). The Gymnasium and SB3 classes are in the Python package around it.

#include <pybind11/pybind11.h>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "envs/registry/registry.hpp"
#include "sim/observation_dict.hpp"

namespace py = pybind11;

namespace upkie_rl::python {

void bind_registry(py::module_& module) {
  module.def("registered_env_ids", &registered_env_ids, "Canonical environment ids.");
  module.def(
      "observation_keys",
      [] {
        std::vector<std::string> leaves;
        for (const ObservationKey& key : observation_keys()) {
          if (!key.is_map) leaves.push_back(key.path);
        }
        return leaves;
      },
      "Dotted paths of every value of the spine observation dictionary "
      "(info['spine_observation']), from its one declaration, the `sim` subtree included.");
  module.def(
      "env_options",
      [](const std::string& id) {
        py::list options;
        for (const OptionInfo& info : env_option_info(id)) {
          static constexpr const char* kTypes[] = {"real",   "integer", "text",
                                                   "choice", "boolean", "integer_list"};
          py::dict option;
          option["name"] = info.name;
          option["type"] = kTypes[static_cast<int>(info.type)];
          option["help"] = info.help;
          option["default"] = info.default_value;
          option["min"] = info.min;
          option["max"] = info.max;
          option["choices"] = info.choices;
          option["randomization"] = info.randomization;
          options.append(std::move(option));
        }
        return options;
      },
      py::arg("env_id"),
      "The options an id accepts: name, type, help, default, bounds, choices, and whether "
      "it is a randomisation (episode conditions) rather than a task option.");
}

}  // namespace upkie_rl::python

PYBIND11_MODULE(_core, module) {
  module.doc() = "upkie-rl environments in C++ (thin bindings; see the upkie_rl package).";
  // Wrong numbers with no error are worse than no module (array_checks.hpp).
  upkie_rl::python::check_numpy_layout();
  // Errors keep their C++ meaning: bad input is ValueError (std::invalid_argument), the
  // upkie_rl::Error hierarchy maps onto upkie_rl.Error (error_bindings.cpp).
  upkie_rl::python::bind_errors(module);
  upkie_rl::python::bind_registry(module);
  upkie_rl::python::bind_env(module);
  upkie_rl::python::bind_vector_env(module);
  upkie_rl::python::bind_policy(module);
  upkie_rl::python::bind_model_files(module);
  upkie_rl::python::bind_evaluation(module);
  upkie_rl::python::bind_argument_ranges(module);
}
