#include "array_checks.hpp"

#include "base/error.hpp"

namespace py = pybind11;

namespace upkie_rl::python {
namespace {

/// "(a, b)" or "(a,)": a shape or strides as numpy prints them.
std::string tuple_text(const py::ssize_t* values, std::size_t size) {
  std::string text = "(";
  for (std::size_t i = 0; i < size; ++i) text += (i ? ", " : "") + std::to_string(values[i]);
  return text + (size == 1 ? ",)" : ")");
}

}  // namespace

void check_layout(const py::array& array, std::size_t item_size, const char* what) {
  const auto ndim = static_cast<std::size_t>(array.ndim());
  bool ok = static_cast<std::size_t>(array.itemsize()) == item_size;
  auto expected_stride = static_cast<py::ssize_t>(item_size);
  for (std::size_t i = ndim; ok && i-- > 0;) {
    // A dimension of one element may have any stride (numpy's own contiguity rule).
    ok = array.shape()[i] <= 1 || array.strides()[i] == expected_stride;
    expected_stride *= array.shape()[i];
  }
  if (ok) return;
  throw Error(std::string(what) + ": numpy reports item size " + std::to_string(array.itemsize()) +
              " and strides " + tuple_text(array.strides(), ndim) +
              " for a C-ordered array of shape " + tuple_text(array.shape(), ndim) + " with " +
              std::to_string(item_size) +
              "-byte items; upkie_rl._core and this NumPy disagree on the array layout "
              "(rebuild the module with pybind11 >= 2.12)");
}

void check_shape(const FloatArray& array, std::size_t rows, std::size_t columns, const char* what) {
  const bool vector = rows == 0;
  const auto ndim = static_cast<std::size_t>(array.ndim());
  const bool ok = vector ? ndim == 1 && static_cast<std::size_t>(array.shape(0)) == columns
                         : ndim == 2 && static_cast<std::size_t>(array.shape(0)) == rows &&
                               static_cast<std::size_t>(array.shape(1)) == columns;
  if (!ok) {
    const std::string expected =
        vector ? "(" + std::to_string(columns) + ",)"
               : "(" + std::to_string(rows) + ", " + std::to_string(columns) + ")";
    throw std::invalid_argument(std::string(what) + " has shape " +
                                tuple_text(array.shape(), ndim) + ", expected " + expected);
  }
  check_layout(array, sizeof(float), what);
}

}  // namespace upkie_rl::python
