#pragma once
/// @file
/// The observation's nested-dictionary view (the Upkie spine's keys) as Python objects:
/// dicts, floats, bools, ints and lists of floats, built straight from the struct by the
/// walk every other view uses (sim/observation_walk.hpp). Needs the GIL.

#include <pybind11/pybind11.h>

#include "sim/observation.hpp"

namespace upkie_rl::python {

/// A new dict, equal to json.loads of observation_to_json(observation).
pybind11::dict observation_to_python(const Observation& observation);

}  // namespace upkie_rl::python
