#include "observation_to_python.hpp"

#include <string_view>
#include <vector>

#include "sim/observation_walk.hpp"

namespace py = pybind11;

namespace upkie_rl::python {
namespace {

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
  py::str key() const { return {key_.data(), key_.size()}; }
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
