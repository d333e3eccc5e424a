#pragma once
/// @file
/// The model files upkie-rl writes: checkpoints (.ckpt), which every runner runs, and the
/// exports made from them (TorchScript .pt, ONNX .onnx) or converted to them (Stable-Baselines3
/// .zip), which `upkie-rl info` describes. One list for the reader that tells them apart
/// (`info`) and for the refusal of the runners (rollout, evaluate, drive, sweep,
/// upkie-rl-agent, `train --resume`, Python's load_policy), which says what to run instead.

#include <filesystem>
#include <string>

namespace upkie_rl {

/// A model file's format.
enum class ModelFormat {
  kCheckpoint,        ///< An upkie-rl checkpoint (any extension but those below).
  kTorchScript,       ///< .pt, written by `upkie-rl train` beside its final checkpoint.
  kOnnx,              ///< .onnx, written by `upkie-rl export`.
  kStableBaselines3,  ///< .zip, read and written by upkie_rl.sb3_convert.
};

/// The format of the model file at `path`, by its extension.
ModelFormat model_format(const std::filesystem::path& path);

/// Why a runner cannot run the model at `path` and what to run instead, for a file that is
/// not a checkpoint: "" when model_format(path) is kCheckpoint.
std::string model_format_refusal(const std::filesystem::path& path);

}  // namespace upkie_rl
