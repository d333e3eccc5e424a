#pragma once
/// @file
/// Shape checks of the numpy arrays the bindings receive, with errors naming what was
/// expected (raised as Python ValueError).

#include <pybind11/numpy.h>

#include <stdexcept>
#include <string>

namespace upkie_rl::python {

/// float32, C-contiguous: what the bindings accept (the Python layer converts to it).
using FloatArray = pybind11::array_t<float, pybind11::array::c_style>;

/// Throws std::invalid_argument unless `array` has `rows` x `columns` values laid out as
/// shape (columns,) when rows is 0, else (rows, columns).
inline void check_shape(const FloatArray& array, std::size_t rows, std::size_t columns,
                        const char* what) {
  const bool vector = rows == 0;
  const auto ndim = static_cast<std::size_t>(array.ndim());
  const bool ok = vector ? ndim == 1 && static_cast<std::size_t>(array.shape(0)) == columns
                         : ndim == 2 && static_cast<std::size_t>(array.shape(0)) == rows &&
                               static_cast<std::size_t>(array.shape(1)) == columns;
  if (!ok) {
    std::string shape = "(";
    for (std::size_t i = 0; i < ndim; ++i) {
      shape += (i ? ", " : "") + std::to_string(array.shape(static_cast<pybind11::ssize_t>(i)));
    }
    shape += ndim == 1 ? ",)" : ")";
    const std::string expected =
        vector ? "(" + std::to_string(columns) + ",)"
               : "(" + std::to_string(rows) + ", " + std::to_string(columns) + ")";
    throw std::invalid_argument(std::string(what) + " has shape " + shape + ", expected " +
                                expected);
  }
}

}  // namespace upkie_rl::python
