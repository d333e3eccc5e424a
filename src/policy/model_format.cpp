#include "policy/model_format.hpp"

#include <system_error>

namespace upkie_rl {

namespace {

/// The checkpoint an export of `path` was made from, when it lies beside it under the same
/// name (as `upkie-rl train` writes model_<date>.ckpt and model_<date>.pt).
std::string checkpoint_beside(const std::filesystem::path& path) {
  std::filesystem::path checkpoint = path;
  checkpoint.replace_extension(".ckpt");
  std::error_code error;
  if (!std::filesystem::is_regular_file(checkpoint, error)) return "";
  return checkpoint.string();
}

/// What to give instead of the export at `path`.
std::string run_its_checkpoint(const std::filesystem::path& path) {
  const std::string beside = checkpoint_beside(path);
  if (!beside.empty()) return "give " + beside + ", the checkpoint beside it";
  return "give the checkpoint (.ckpt) it was made from (`upkie-rl info " + path.string() +
         "` shows its provenance)";
}

}  // namespace

ModelFormat model_format(const std::filesystem::path& path) {
  const std::string extension = path.extension().string();
  if (extension == ".pt") return ModelFormat::kTorchScript;
  if (extension == ".onnx") return ModelFormat::kOnnx;
  if (extension == ".zip") return ModelFormat::kStableBaselines3;
  return ModelFormat::kCheckpoint;
}

std::string model_format_refusal(const std::filesystem::path& path) {
  const std::string model = "model " + path.string();
  switch (model_format(path)) {
    case ModelFormat::kCheckpoint:
      return "";
    case ModelFormat::kTorchScript:
      return model +
             " is a TorchScript export, which upkie-rl describes (`info`) but does not "
             "run: " +
             run_its_checkpoint(path);
    case ModelFormat::kOnnx:
      return model + " is an ONNX export, which upkie-rl describes (`info`) but does not run: " +
             run_its_checkpoint(path) + "; an ONNX runtime runs it (docs/interop.md)";
    case ModelFormat::kStableBaselines3:
      return model + " is a Stable-Baselines3 zip: `python3 -m upkie_rl.sb3_convert import " +
             path.string() + " --env ENV -o MODEL.ckpt` converts it into a checkpoint " +
             "(`... info " + path.string() + "` describes it; docs/interop.md)";
  }
  return "";
}

}  // namespace upkie_rl
