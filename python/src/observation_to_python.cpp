#include "observation_to_python.hpp"

#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "sim/observation_walk.hpp"

namespace py = pybind11;

namespace upkie_rl::python {
namespace {

/// Interned Python strings of the walk's keys, made once: the keys are string literals and
/// joint names, so the text behind a pointer never changes (checked anyway). Halves the
/// cost of a dictionary. Used with the GIL held; the strings live as long as the process.
py::handle interned_key(std::string_view key) {
  static auto* cache = new std::unordered_map<const char*, std::pair<std::string, py::handle>>();
  auto found = cache->find(key.data());
  if (found != cache->end() && found->second.first == key) return found->second.second;
  PyObject* text = PyUnicode_FromStringAndSize(key.data(), static_cast<py::ssize_t>(key.size()));
  if (text == nullptr) throw py::error_already_set();
  PyUnicode_InternInPlace(&text);
  (*cache)[key.data()] = {std::string(key), py::handle(text)};
  return text;
}

/// Builds Python objects with a stack of open dicts (the writer interface of
/// walk_observation).
class PythonWriter {
 public:
  PythonWriter() { stack_.reserve(8); }
  void begin_map(std::size_t) {
    py::dict map;
    if (!stack_.empty()) stack_.back()[key()] = map;
    stack_.push_back(std::move(map));
  }
  void end_map() {
    if (stack_.size() == 1) root_ = stack_.back();
    stack_.pop_back();
  }
  void key(std::string_view key) { key_ = key; }
  void real(double value) { stack_.back()[key()] = py::float_(value); }
  void boolean(bool value) { stack_.back()[key()] = py::bool_(value); }
  void integer(int value) { stack_.back()[key()] = py::int_(value); }
  void reals(const double* values, std::size_t size) {
    py::list list(size);
    for (std::size_t i = 0; i < size; ++i) list[i] = py::float_(values[i]);
    stack_.back()[key()] = std::move(list);
  }
  py::dict root() { return root_; }

 private:
  py::handle key() const { return interned_key(key_); }
  py::dict root_;
  std::vector<py::dict> stack_;
  std::string_view key_;
};

}  // namespace

py::dict observation_to_python(const Observation& observation) {
  PythonWriter writer;
  walk_observation(observation, writer);
  return writer.root();
}

}  // namespace upkie_rl::python
