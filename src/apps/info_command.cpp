/// @file
/// `upkie-rl info MODEL`: what a model is and how it was made (its provenance), for the
/// checkpoint (.ckpt), TorchScript (.pt) and ONNX (.onnx) files upkie-rl writes.

#include <caffe2/serialize/inline_container.h>

#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "apps/commands.hpp"
#include "cli/command_error.hpp"
#include "onnx/onnx_metadata.hpp"
#include "onnx/onnx_model_info.hpp"
#include "policy/checkpoint_gate.hpp"
#include "policy/checkpoint_header.hpp"
#include "policy/model_format.hpp"
#include "policy/model_header.hpp"
#include "policy/provenance.hpp"
#include "policy/space_json.hpp"

namespace upkie_rl::apps {

namespace {

namespace key = checkpoint_header;

// "4: theta, p, theta_dot, p_dot"
std::string describe_space(const nlohmann::json& json) {
  const BoxSpace space = space_from_json(json);
  std::string text = std::to_string(space.size());
  for (std::size_t i = 0; i < space.names.size(); ++i) {
    text += (i == 0 ? ": " : ", ") + space.names[i];
  }
  return text;
}

void print_checkpoint(const std::filesystem::path& path) {
  const CheckpointFile file = read_checked_checkpoint(path);  // the gate of every command
  std::cout << "format: upkie-rl checkpoint\n"
            << key::kObservationSpace << ": "
            << describe_space(file.header.at(key::kObservationSpace)) << "\n"
            << key::kActionSpace << ": " << describe_space(file.header.at(key::kActionSpace))
            << "\n"
            << key::kPolicy << ": "
            << policy_shape_to_json(policy_shape_from_json(file.header.at(key::kPolicy))).dump()
            << "\n"
            << format_provenance(model_provenance(file.header));
}

void print_onnx(const std::filesystem::path& path) {
  const OnnxModelInfo info = read_onnx_model_info(path);
  std::cout << "format: ONNX (IR " << info.ir_version << ", opset " << info.opset << ", by "
            << info.producer_name << " " << info.producer_version << ")\n";
  auto print_tensors = [](const char* what, const std::vector<OnnxTensorInfo>& tensors) {
    for (const OnnxTensorInfo& tensor : tensors) {
      std::cout << what << ": " << tensor.name << " " << tensor.element_type << " [";
      for (std::size_t i = 0; i < tensor.shape.size(); ++i) {
        std::cout << (i ? ", " : "") << tensor.shape[i];
      }
      std::cout << "]\n";
    }
  };
  print_tensors("input", info.inputs);
  print_tensors("output", info.outputs);
  nlohmann::json provenance;
  for (const auto& [key, value] : info.metadata) {
    if (key == onnx_names::kProvenance) {
      provenance = nlohmann::json::parse(value, nullptr, false);
    } else if (key == onnx_names::kEnvId || key == onnx_names::kEnvOptions) {
      continue;  // The provenance below shows them.
    } else if (key == onnx_names::kObservationSpace || key == onnx_names::kActionSpace) {
      const nlohmann::json space = nlohmann::json::parse(value, nullptr, false);
      std::cout << key << ": " << (space.is_discarded() ? value : describe_space(space)) << "\n";
    } else {
      std::cout << key << ": " << value << "\n";
    }
  }
  if (!provenance.is_object()) provenance = nlohmann::json::object();
  std::cout << format_provenance(model_provenance({{checkpoint_header::kProvenance, provenance}}));
}

void print_torchscript(const std::filesystem::path& path) {
  // Only the archive's metadata record is read: the module itself is not loaded.
  std::string text;
  try {
    caffe2::serialize::PyTorchStreamReader reader(path.string());
    const char* record = "extra/metadata.json";
    if (!reader.hasRecord(record)) {
      throw CommandError("TorchScript file " + path.string() +
                         " has no upkie-rl metadata (not exported by upkie-rl)");
    }
    auto [data, size] = reader.getRecord(record);
    text.assign(static_cast<const char*>(data.get()), size);
  } catch (const c10::Error& error) {
    throw CommandError("TorchScript file " + path.string() +
                       ": unreadable archive: " + error.what_without_backtrace());
  }
  const nlohmann::json metadata = nlohmann::json::parse(text, nullptr, false);
  if (!metadata.is_object()) {
    throw CommandError("TorchScript file " + path.string() + ": malformed metadata.json");
  }
  std::cout << "format: TorchScript\n";
  // The metadata's entries are named as those of the checkpoint header they copy, and its
  // env id as the provenance's (rl/runs/torchscript_export.cpp).
  for (const char* key : {checkpoint_header::kObservationSpace, checkpoint_header::kActionSpace}) {
    if (metadata.contains(key)) std::cout << key << ": " << describe_space(metadata[key]) << "\n";
  }
  nlohmann::json provenance =
      metadata.value(checkpoint_header::kProvenance, nlohmann::json::object());
  if (!provenance.is_object()) provenance = nlohmann::json::object();
  if (!provenance.contains(provenance_key::kEnvId) && metadata.contains(provenance_key::kEnvId)) {
    provenance[provenance_key::kEnvId] = metadata[provenance_key::kEnvId];
  }
  std::cout << format_provenance(model_provenance({{checkpoint_header::kProvenance, provenance}}));
}

void print_info(const std::filesystem::path& path) {
  const ModelFormat format = model_format(path);
  // The converter's own `info` reads an SB3 zip (its pickles are not read here).
  if (format == ModelFormat::kStableBaselines3) {
    throw CommandError(model_format_refusal(path));
  }
  std::cout << "model: " << path.string() << "\n";
  if (format == ModelFormat::kOnnx) {
    print_onnx(path);
  } else if (format == ModelFormat::kTorchScript) {
    print_torchscript(path);
  } else {
    print_checkpoint(path);
  }
  std::cout << std::flush;
}

}  // namespace

void add_info_command(CLI::App& app) {
  auto model = std::make_shared<std::string>();
  CLI::App* command =
      app.add_subcommand("info", "Describe a model (.ckpt, .pt, .onnx): spaces and provenance");
  command->add_option("model", *model, "Model file")->required()->check(CLI::ExistingFile);
  command->callback([model] { print_info(*model); });
}

}  // namespace upkie_rl::apps
