#pragma once
/// @file
/// The pieces of the `upkie_rl._core` extension module, one binding function per file.

#include <pybind11/pybind11.h>

#include "envs/spaces/box_space.hpp"

namespace upkie_rl::python {

/// (low, high, names) of a Box space, low and high as float32 arrays.
pybind11::tuple space_to_python(const BoxSpace& space);

/// Raises ImportError unless NumPy reads the arrays this module makes as it wrote them
/// (numpy_layout_check.cpp); call it first.
void check_numpy_layout();
/// The upkie_rl::Error hierarchy as Python classes under `upkie_rl.Error`, and their
/// translation; call it before the other bindings.
void bind_errors(pybind11::module_& module);
void bind_env(pybind11::module_& module);
void bind_vector_env(pybind11::module_& module);
void bind_registry(pybind11::module_& module);
void bind_policy(pybind11::module_& module);
void bind_model_files(pybind11::module_& module);
void bind_evaluation(pybind11::module_& module);
/// `ARGUMENT_RANGES`: (min, max) of each integer argument the package checks.
void bind_argument_ranges(pybind11::module_& module);

}  // namespace upkie_rl::python
