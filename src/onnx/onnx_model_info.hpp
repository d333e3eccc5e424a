#pragma once
/// @file
/// What an ONNX file says of itself, read without running it: producer, opset, inputs and
/// outputs with their shapes, and metadata properties (an upkie-rl export's environment,
/// spaces, frequency and provenance).

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace upkie_rl {

/// One graph input or output: name, element type and shape ("batch" for a symbolic size).
struct OnnxTensorInfo {
  std::string name;
  std::string element_type;
  std::vector<std::string> shape;
};

/// The description of an ONNX model.
struct OnnxModelInfo {
  std::string producer_name;
  std::string producer_version;
  std::int64_t ir_version = 0;
  std::int64_t opset = 0;  ///< Of the default domain.
  std::vector<OnnxTensorInfo> inputs;
  std::vector<OnnxTensorInfo> outputs;
  std::map<std::string, std::string> metadata;
};

/// Largest ONNX file read (bytes): a policy takes kilobytes to megabytes; a larger file is
/// refused before it is read rather than allocated whole.
inline constexpr std::uintmax_t kMaxOnnxFileBytes = std::uintmax_t{256} << 20;

/// Reads and checks (ONNX checker) the model at `path`. Throws OnnxError naming the file
/// and the problem: missing, too large, not an ONNX model, or an invalid one.
OnnxModelInfo read_onnx_model_info(const std::filesystem::path& path);

}  // namespace upkie_rl
