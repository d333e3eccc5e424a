// The C++ error hierarchy (base/error.hpp) as Python classes, declared in this one place.

#include <Python.h>
#include <pybind11/pybind11.h>

#include <array>
#include <exception>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "base/error.hpp"
#include "bindings.hpp"
#include "model/robot_model.hpp"
#include "onnx/onnx_error.hpp"
#include "policy/checkpoint_file.hpp"
#include "policy/policy_output_error.hpp"
#include "render/render_error.hpp"
#include "sim/servo_command.hpp"
#include "sim/simulation.hpp"
#include "spine/spine_error.hpp"

namespace py = pybind11;

namespace upkie_rl::python {

namespace {

/// One Python class of the hierarchy: the C++ class it stands for, its Python parent in
/// the hierarchy (an index into kErrorClasses, -1 for the root) and the built-in exception
/// it also derives from, so that code catching ValueError or RuntimeError keeps working.
struct ErrorClass {
  const char* name;
  const char* doc;
  bool (*matches)(const Error&);
  int parent;
  PyObject* const* builtin;
};

template <class T>
bool is(const Error& error) {
  // Every Error is an Error: no cast (comparing the address of a reference with null is
  // always false, which -Wnonnull-compare flags).
  if constexpr (std::is_same_v<T, Error>) {
    return true;
  } else {
    return dynamic_cast<const T*>(&error) != nullptr;
  }
}

// Parents come before their children; the translator tries the most derived class first.
// The Python module has no view or rl layer, so ViewError and DistributedError (which
// only the `upkie-rl` tool raises) are not bound; nor is RobotLogError: the module reads no
// robot logs (`upkie-rl identify` and `spine --log` do).
const std::array kErrorClasses = {
    ErrorClass{"Error", "Base of every error upkie-rl raises on purpose.", &is<Error>, -1,
               &PyExc_RuntimeError},
    ErrorClass{"ModelError", "A robot description cannot be read.", &is<ModelError>, 0,
               &PyExc_RuntimeError},
    ErrorClass{"SimulationDivergedError", "The simulated state stopped being finite.",
               &is<SimulationDivergedError>, 0, &PyExc_RuntimeError},
    ErrorClass{"InvalidCommandError", "A servo command is not acceptable (NaN, infinite).",
               &is<InvalidCommandError>, 0, &PyExc_ValueError},
    ErrorClass{"RenderError", "A frame or a video cannot be made.", &is<RenderError>, 0,
               &PyExc_RuntimeError},
    ErrorClass{"SpineError", "A spine link failure.", &is<SpineError>, 0, &PyExc_RuntimeError},
    ErrorClass{"SpineTimeoutError", "The spine did not process a request in time.",
               &is<SpineTimeoutError>, 5, &PyExc_RuntimeError},
    ErrorClass{"CheckpointError", "A missing, truncated, corrupted or inconsistent checkpoint.",
               &is<CheckpointError>, 0, &PyExc_ValueError},
    ErrorClass{"OnnxError", "A model that cannot be exported, or an unreadable ONNX file.",
               &is<OnnxError>, 0, &PyExc_ValueError},
    ErrorClass{"PolicyOutputError", "A policy's action is not finite for the observation given.",
               &is<PolicyOutputError>, 0, &PyExc_RuntimeError},
};

std::array<PyObject*, kErrorClasses.size()> python_classes{};

/// `message` on one line: control characters (a newline in an id or an option's value that
/// the message quotes) written as escapes, "\n", "\x01", so that no error spans lines.
std::string one_line(const char* message) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string line;
  for (const char* c = message; *c != '\0'; ++c) {
    const auto byte = static_cast<unsigned char>(*c);
    if (byte == '\n') {
      line += "\\n";
    } else if (byte == '\r') {
      line += "\\r";
    } else if (byte == '\t') {
      line += "\\t";
    } else if (byte < 0x20 || byte == 0x7f) {
      line += std::string("\\x") + kHex[byte >> 4] + kHex[byte & 0xf];
    } else {
      line += *c;
    }
  }
  return line;
}

/// The Python exception of a C++ one, its message on one line: the hierarchy's classes,
/// and pybind11's usual built-in ones for the standard exceptions (others, such as
/// std::bad_alloc, rethrown to pybind11's own translator).
void set_python_error(std::exception_ptr pointer) {
  try {
    std::rethrow_exception(pointer);
  } catch (const Error& error) {
    for (std::size_t i = kErrorClasses.size(); i-- > 0;) {
      if (kErrorClasses[i].matches(error)) {
        PyErr_SetString(python_classes[i], one_line(error.what()).c_str());
        return;
      }
    }
    PyErr_SetString(PyExc_RuntimeError, one_line(error.what()).c_str());
  } catch (const std::invalid_argument& error) {
    PyErr_SetString(PyExc_ValueError, one_line(error.what()).c_str());
  } catch (const std::domain_error& error) {
    PyErr_SetString(PyExc_ValueError, one_line(error.what()).c_str());
  } catch (const std::length_error& error) {
    PyErr_SetString(PyExc_ValueError, one_line(error.what()).c_str());
  } catch (const std::out_of_range& error) {
    PyErr_SetString(PyExc_IndexError, one_line(error.what()).c_str());
  } catch (const std::range_error& error) {
    PyErr_SetString(PyExc_ValueError, one_line(error.what()).c_str());
  } catch (const std::overflow_error& error) {
    PyErr_SetString(PyExc_OverflowError, one_line(error.what()).c_str());
  } catch (const std::runtime_error& error) {
    PyErr_SetString(PyExc_RuntimeError, one_line(error.what()).c_str());
  }
}

PyObject* make_class(py::module_& module, const ErrorClass& error) {
  // The parent class (none for the root), and the built-in exception unless the parent
  // derives from it already: CheckpointError is (Error, ValueError), SpineError (Error,).
  py::list bases;
  if (error.parent >= 0) bases.append(py::handle(python_classes[error.parent]));
  if (error.parent < 0 || PyObject_IsSubclass(python_classes[error.parent], *error.builtin) != 1) {
    bases.append(py::handle(*error.builtin));
  }
  const std::string qualified = std::string("upkie_rl.") + error.name;
  PyObject* type =
      PyErr_NewExceptionWithDoc(qualified.c_str(), error.doc, py::tuple(bases).ptr(), nullptr);
  if (type == nullptr) throw py::error_already_set();
  module.add_object(error.name, py::handle(type));  // adds the module's own reference
  return type;
}

}  // namespace

void bind_errors(py::module_& module) {
  for (std::size_t i = 0; i < kErrorClasses.size(); ++i) {
    python_classes[i] = make_class(module, kErrorClasses[i]);
  }
  // Other exceptions (std::runtime_error, std::bad_alloc, ...) are left to pybind11: its
  // translator runs when this one rethrows them.
  py::register_exception_translator([](std::exception_ptr pointer) {
    if (pointer) set_python_error(pointer);
  });
}

}  // namespace upkie_rl::python
