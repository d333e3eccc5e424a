#pragma once
/// @file
/// Export of a trained policy as an ONNX model that any ONNX runtime runs: the deterministic
/// actor with the frozen observation normalisation before it and the action clipping after
/// it, so that `action = model(observation)` on raw float32 observations of shape
/// (batch, observation size) gives DeployedPolicy's actions. Built with the ONNX project's
/// protobuf classes and checked by its checker (Debian's libonnx-dev); opset 13.
/// The model's metadata properties (onnx/onnx_metadata.hpp) name the environment id and
/// options, the spaces, the control frequency and the provenance.

#include <filesystem>

#include <nlohmann/json.hpp>

#include "policy/deployed_policy.hpp"

namespace upkie_rl {

/// The ONNX opset the export uses (Clip with min/max inputs needs 11, Gemm's defaults 13).
inline constexpr int kOnnxOpset = 13;

/// Writes `policy` to `path` as ONNX; `provenance` (policy/provenance.hpp) goes into the
/// metadata. Throws OnnxError naming the file on a write failure or a model the checker
/// refuses.
void export_onnx(const DeployedPolicy& policy, const nlohmann::json& provenance,
                 const std::filesystem::path& path);

/// Reads the model or checkpoint at `model_path` and exports it to `onnx_path`.
/// Throws CheckpointError for a bad model file, OnnxError for a failed export.
void export_onnx_file(const std::filesystem::path& model_path,
                      const std::filesystem::path& onnx_path);

}  // namespace upkie_rl
