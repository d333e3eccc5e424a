// check_numpy_layout: refuses to import the module into a NumPy that would read its arrays
// wrongly (array_checks.hpp says why such a build gave copies of the first element).

#include <pybind11/numpy.h>

#include <string>

#include "array_checks.hpp"
#include "bindings.hpp"

namespace py = pybind11;

namespace upkie_rl::python {
namespace {

/// The numbers NumPy reads from a (2, 3) float32 array and a (2, 2, 3) uint8 array the
/// module filled with 0, 1, 2...: its own view of them, through `tolist`.
bool numpy_reads_what_was_written() {
  py::array_t<float> floats = new_array<float>({2, 3}, "float32 probe");
  py::array_t<std::uint8_t> bytes = new_array<std::uint8_t>({2, 2, 3}, "uint8 probe");
  for (py::ssize_t i = 0; i < floats.size(); ++i) floats.mutable_data()[i] = static_cast<float>(i);
  for (py::ssize_t i = 0; i < bytes.size(); ++i)
    bytes.mutable_data()[i] = static_cast<std::uint8_t>(i);
  const py::object flat_floats = floats.attr("ravel")().attr("tolist")();
  const py::object flat_bytes = bytes.attr("ravel")().attr("tolist")();
  py::list expected_floats;
  py::list expected_bytes;
  for (int i = 0; i < 6; ++i) expected_floats.append(py::float_(static_cast<double>(i)));
  for (int i = 0; i < 12; ++i) expected_bytes.append(py::int_(i));
  return flat_floats.equal(expected_floats) && flat_bytes.equal(expected_bytes);
}

}  // namespace

void check_numpy_layout() {
  const std::string numpy_version =
      py::module_::import("numpy").attr("__version__").cast<std::string>();
  const std::string versions = "NumPy " + numpy_version + ", pybind11 " +
                               std::to_string(PYBIND11_VERSION_MAJOR) + "." +
                               std::to_string(PYBIND11_VERSION_MINOR);
  try {
    if (numpy_reads_what_was_written()) return;
  } catch (const std::exception& error) {
    throw py::import_error("upkie_rl._core (" + versions + "): " + error.what());
  }
  throw py::import_error("upkie_rl._core (" + versions +
                         "): NumPy reads other numbers than the module wrote into its arrays; "
                         "rebuild the module with pybind11 >= 2.12");
}

}  // namespace upkie_rl::python
