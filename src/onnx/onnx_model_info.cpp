#include "onnx/onnx_model_info.hpp"

#include <onnx/checker.h>
#include <onnx/onnx_pb.h>

#include <iterator>
#include <system_error>

#include "base/input_file.hpp"
#include "onnx/onnx_error.hpp"

namespace upkie_rl {

namespace {

OnnxTensorInfo tensor_info(const onnx::ValueInfoProto& value) {
  OnnxTensorInfo info;
  info.name = value.name();
  if (!value.type().has_tensor_type()) {
    info.element_type = "not a tensor";
    return info;
  }
  const onnx::TypeProto_Tensor& tensor = value.type().tensor_type();
  info.element_type = onnx::TensorProto_DataType_Name(tensor.elem_type());
  for (const onnx::TensorShapeProto_Dimension& dim : tensor.shape().dim()) {
    info.shape.push_back(dim.has_dim_value() ? std::to_string(dim.dim_value()) : dim.dim_param());
  }
  return info;
}

}  // namespace

OnnxModelInfo read_onnx_model_info(const std::filesystem::path& path) {
  const std::string bytes = read_input_file<OnnxError>(path, "ONNX model", kMaxOnnxFileBytes);
  onnx::ModelProto model;
  if (bytes.empty() || !model.ParseFromString(bytes) || !model.has_graph()) {
    throw OnnxError("ONNX model " + path.string() +
                    ": not an ONNX model (not a ModelProto protobuf with a graph)");
  }
  try {
    onnx::checker::check_model(model);
  } catch (const std::exception& error) {
    throw OnnxError("ONNX model " + path.string() + ": invalid: " + error.what());
  }
  OnnxModelInfo info;
  info.producer_name = model.producer_name();
  info.producer_version = model.producer_version();
  info.ir_version = model.ir_version();
  for (const onnx::OperatorSetIdProto& opset : model.opset_import()) {
    if (opset.domain().empty() || opset.domain() == "ai.onnx") info.opset = opset.version();
  }
  for (const onnx::ValueInfoProto& input : model.graph().input()) {
    info.inputs.push_back(tensor_info(input));
  }
  for (const onnx::ValueInfoProto& output : model.graph().output()) {
    info.outputs.push_back(tensor_info(output));
  }
  for (const onnx::StringStringEntryProto& entry : model.metadata_props()) {
    info.metadata[entry.key()] = entry.value();
  }
  return info;
}

}  // namespace upkie_rl
