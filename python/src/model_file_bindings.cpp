// Python bindings of model files: checkpoint reading and writing (for the Stable-Baselines3
// converter, upkie_rl/sb3_convert.py), provenance, and ONNX export.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cctype>
#include <span>
#include <string>
#include <string_view>

#include "array_checks.hpp"
#include "bindings.hpp"
#include "onnx/onnx_error.hpp"
#include "onnx/onnx_export.hpp"
#include "policy/activation.hpp"
#include "policy/checkpoint_file.hpp"
#include "policy/checkpoint_gate.hpp"
#include "policy/checkpoint_header.hpp"
#include "policy/deployed_policy.hpp"
#include "policy/model_header.hpp"
#include "policy/provenance.hpp"
#include "vec/normalization_state.hpp"

namespace py = pybind11;

namespace upkie_rl::python {
namespace {

// (header as JSON text, {name: float32 array}) of a checkpoint, checked as a model.
py::tuple read_model_checkpoint(const std::string& path) {
  CheckpointFile file = read_checked_checkpoint(path);  // The gate of every command.
  py::dict tensors;
  for (auto& [name, tensor] : file.tensors) {
    py::array_t<float> array = new_array<float>(
        std::vector<py::ssize_t>(tensor.shape.begin(), tensor.shape.end()), name.c_str());
    std::copy(tensor.values.begin(), tensor.values.end(), array.mutable_data());
    tensors[py::str(name)] = array;
  }
  return py::make_tuple(file.header.dump(), tensors);
}

// Writes a checkpoint from JSON header text and {name: float32 array}, then reads it back
// as a model so that a converter cannot write a file the other commands refuse.
void write_model_checkpoint(const std::string& path, const std::string& header,
                            const py::dict& tensors) {
  CheckpointFile file;
  file.header = nlohmann::json::parse(header);
  for (const auto& [name, value] : tensors) {
    const auto array =
        py::cast<py::array_t<float, py::array::c_style | py::array::forcecast>>(value);
    check_layout(array, sizeof(float), "tensor");
    FloatTensor tensor;
    for (py::ssize_t i = 0; i < array.ndim(); ++i) tensor.shape.push_back(array.shape(i));
    tensor.values.assign(array.data(), array.data() + array.size());
    file.tensors[py::cast<std::string>(name)] = std::move(tensor);
  }
  DeployedPolicy::from_checkpoint(file, "converted model " + path);
  write_checkpoint_file(file, path);
}

// A key's Python name: its C++ constant's without the k, in upper snake case
// ("kNumTimesteps" -> "NUM_TIMESTEPS", "kNUpdates" -> "N_UPDATES").
std::string python_name(std::string_view constant) {
  const std::string_view name = constant.substr(1);
  std::string upper;
  for (std::size_t i = 0; i < name.size(); ++i) {
    const bool starts_word =
        i > 0 && std::isupper(static_cast<unsigned char>(name[i])) &&
        (std::islower(static_cast<unsigned char>(name[i - 1])) ||
         (i + 1 < name.size() && std::islower(static_cast<unsigned char>(name[i + 1]))));
    if (starts_word) upper += '_';
    upper += static_cast<char>(std::toupper(static_cast<unsigned char>(name[i])));
  }
  return upper;
}

// {Python name: wire text} of every key of one declared list.
py::dict python_keys(std::span<const NamedKey> declared) {
  py::dict keys;
  for (const NamedKey& key : declared) keys[py::str(python_name(key.constant))] = key.text;
  return keys;
}

}  // namespace

void bind_model_files(py::module_& module) {
  module.def("read_model_checkpoint", &read_model_checkpoint, py::arg("path"),
             "(header JSON text, {tensor name: float32 array}) of a model or checkpoint.");
  module.def(
      "write_model_checkpoint", &write_model_checkpoint, py::arg("path"), py::arg("header"),
      py::arg("tensors"),
      "Writes a checkpoint (header JSON text, {name: float32 array}) that loads as a model.");
  module.def(
      "new_provenance", [](const std::string& source) { return new_provenance(source).dump(); },
      py::arg("source"), "Provenance entry (JSON text) of a model made now by this build.");
  module.def(
      "model_provenance",
      [](const std::string& header) {
        return model_provenance(nlohmann::json::parse(header)).dump();
      },
      py::arg("header"), "Complete provenance (JSON text) of a checkpoint header (JSON text).");
  module.def(
      "checkpoint_header_keys", [] { return python_keys(checkpoint_header::kAllKeys); },
      "{name: key} of every key of a checkpoint's JSON header and tensors, from their one "
      "declaration (e.g. NUM_TIMESTEPS: 'num_timesteps').");
  module.def(
      "normalization_state_keys", [] { return python_keys(normalization_state::kAllKeys); },
      "{name: key} of every key of the normalisation state (a header's normalization entry), "
      "from their one declaration (e.g. CLIP_OBSERVATIONS: 'clip_observations').");
  module.def(
      "provenance_keys", [] { return python_keys(provenance_key::kAllKeys); },
      "{name: key} of every key of a model's provenance, from their one declaration "
      "(e.g. ENV_ID: 'env_id').");
  module.def(
      "checkpoint_format", [] { return py::make_tuple(kCheckpointFormat, kCheckpointVersion); },
      "(format text, version) that a checkpoint header's format and version entries hold.");
  module.def(
      "activation_torch_names",
      [] {
        py::dict names;
        for (const auto& [spelling, activation] : activation_spellings()) {
          if (spelling != activation_name(activation)) {
            names[py::str(spelling)] = activation_name(activation);
          }
        }
        return names;
      },
      "{PyTorch class name: upkie-rl's name} of every activation (policy/activation.hpp), "
      "e.g. LeakyReLU: 'leaky_relu'.");
  module.def(
      "export_onnx",
      [](const std::string& model, const std::string& onnx) {
        py::gil_scoped_release release;
        export_onnx_file(model, onnx);
      },
      py::arg("model"), py::arg("onnx"), "Exports a model or checkpoint as an ONNX policy.");
}

}  // namespace upkie_rl::python
