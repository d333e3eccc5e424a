#pragma once
/// @file
/// Checks of the numpy arrays that cross the module's boundary, with errors naming what was
/// expected: the shape of what the bindings receive (raised as Python ValueError), and the
/// memory layout of every array they make or receive (raised as upkie_rl.Error).
///
/// Why the layout: pybind11 before 2.12 read NumPy's array descriptor with NumPy 1's
/// struct layout. Under NumPy 2 it took a wrong item size, made arrays whose strides were
/// 0, and every element of an observation read as a copy of the first, with no error. The
/// build now takes a pybind11 that knows NumPy 2 (python/CMakeLists.txt); these checks make
/// any other mismatch between the module and the NumPy it runs with raise instead of
/// returning wrong numbers. They cost a few comparisons per array.

#include <pybind11/numpy.h>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace upkie_rl::python {

/// float32, C-contiguous: what the bindings accept (the Python layer converts to it).
using FloatArray = pybind11::array_t<float, pybind11::array::c_style>;

/// `size` as a numpy dimension.
inline pybind11::ssize_t as_size(std::size_t size) { return static_cast<pybind11::ssize_t>(size); }

/// Throws upkie_rl::Error unless `array` holds items of `item_size` bytes laid out in C
/// order (each stride the product of the item size and the later dimensions).
void check_layout(const pybind11::array& array, std::size_t item_size, const char* what);

/// A new C-contiguous array of `shape`, its layout checked (check_layout).
template <typename T>
pybind11::array_t<T> new_array(std::vector<pybind11::ssize_t> shape, const char* what) {
  pybind11::array_t<T, pybind11::array::c_style> array(std::move(shape));
  check_layout(array, sizeof(T), what);
  return array;
}

/// Throws std::invalid_argument unless `array` has `rows` x `columns` values laid out as
/// shape (columns,) when rows is 0, else (rows, columns); then checks its layout.
void check_shape(const FloatArray& array, std::size_t rows, std::size_t columns, const char* what);

}  // namespace upkie_rl::python
